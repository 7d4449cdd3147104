// Case 11, degenerate input: every stress scene named degenerate-* must either
// fail to load with one clear line naming the file and the faulty field, or
// (the zero-area triangle) load with a warning naming it and render without
// it. Nothing may crash or reach the renderer as NaN.
#include "stability.hpp"

#include "scene/validate.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

std::string load_error(const std::string& name) {
    try {
        (void)load_scene(stress_path(name));
    } catch (const SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

} // namespace

TEST_CASE("degenerate input: each bad scene fails with one line naming its field",
          "[stability][degenerate]") {
    struct Case {
        const char* scene;
        const char* pointer;
        const char* problem;
    };
    const Case cases[] = {
        {"degenerate-inf-coordinate", "/shapes/0/vertices/1/0", "out of range"},
        {"degenerate-huge-coordinate", "/shapes/0/vertices/2/1", "too large for float32"},
        {"degenerate-negative-radius", "/shapes/2/radius", "must be positive"},
        {"degenerate-zero-resolution", "/camera/resolution/0", "positive number of pixels"},
        {"degenerate-up-parallel", "/camera/up", "parallel to the view direction"},
        {"degenerate-huge-radiance", "/materials/light/radiance/1", "at most 1e30"},
    };
    for (const Case& c : cases) {
        std::string message = load_error(c.scene);
        INFO(c.scene << ": " << message);
        CHECK(message.find(std::string(c.scene) + ".json") != std::string::npos);
        CHECK(message.find(std::string(": ") + c.pointer + ": ") != std::string::npos);
        CHECK(message.find(c.problem) != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("degenerate input: a NaN coordinate cannot be written in JSON, and a scene built in "
          "code with one is rejected by name",
          "[stability][degenerate]") {
    // JSON has no NaN: the literal is a syntax error at its position.
    std::string json = R"({"camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0],
        "fov": 60, "resolution": [8, 8]},
        "materials": {"white": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}},
        "shapes": [{"type": "triangle", "material": "white",
                    "vertices": [[0, 0, 0], [1, NaN, 0], [0, 1, 0]]}]})";
    try {
        (void)parse_scene(json, "nan.json");
        FAIL("a NaN literal was accepted");
    } catch (const SceneError& e) {
        std::string message = e.what();
        INFO(message);
        CHECK(message.find("nan.json:5:") == 0);
        CHECK(message.find("/shapes/0/vertices/1/1") != std::string::npos);
    }
    // Built in code, validate_scene names the field; rendered anyway (the
    // integrator trusts its caller), the film's guard keeps the image finite.
    Scene scene = load_scene(stress_path("degenerate-zero-area"));
    Triangle broken = scene.triangles[0];
    broken.v[1].y = std::nan("");
    scene.triangles.set(0, broken);
    try {
        validate_scene(scene);
        FAIL("validate_scene accepted a NaN vertex");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()).find("triangles[0].v[1][1]: must be finite") !=
              std::string::npos);
    }
    scene.camera.width = scene.camera.height = 16;
    test::Rendered r = test::render(scene, 4);
    Image mean = r.film.mean();
    bool finite = true;
    for (float v : mean.rgb)
        finite = finite && std::isfinite(v);
    WARN("NaN vertex rendered anyway: " << r.stats.nonfinite_samples
                                        << " non-finite samples dropped at the film");
    CHECK(finite);
}

TEST_CASE("degenerate input: a zero-area triangle is skipped with a warning naming it",
          "[stability][degenerate]") {
    Scene scene = load_scene(stress_path("degenerate-zero-area"));
    REQUIRE(scene.warnings.size() == 1);
    CHECK(scene.warnings[0].find("/shapes/2") != std::string::npos);
    CHECK(scene.warnings[0].find("zero-area") != std::string::npos);
    CHECK(scene.triangles.size() == 4); // the floor's and the light's two each
    scene.camera.width = scene.camera.height = 16;
    test::Rendered r = test::render(scene, 4);
    CHECK(all_finite(r));
}
