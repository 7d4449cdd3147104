// The loader on input that is valid JSON but extreme: values nested far too
// deep fail with one message instead of overflowing the stack, a scene with
// 10^5 materials loads in linear time, and a scene without light is known.
#include <catch2/catch.hpp>

#include <ctime>
#include <string>
#include <vector>

#include "scene/json_reader.hpp"
#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "support/sanitizer.hpp"

namespace {

const std::string kCamera =
    R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})";

std::string triangle(const std::string& material) {
    return R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": ")" +
           material + R"("})";
}

} // namespace

TEST_CASE("loader: deeply nested values fail with the nesting limit, not a crash",
          "[scene][load]") {
    for (const std::size_t depth : {std::size_t{65}, std::size_t{100000}, std::size_t{2000000}}) {
        INFO("depth " << depth);
        // Nested arrays inside a field, then nested objects.
        // (Built with append: `"1" + std::string` trips a GCC 12 -Wrestrict false positive.)
        std::string arrays = R"({"description": )";
        arrays.append(depth, '[').append(depth, ']').append("}");
        std::string objects = R"({"camera": )";
        for (std::size_t i = 0; i < depth; ++i)
            objects += R"({"a": )";
        objects.append("1").append(depth, '}').append("}");
        for (const std::string& text : {arrays, objects}) {
            try {
                wp::parse_scene(text, "deep.json");
                FAIL("no error");
            } catch (const wp::SceneError& e) {
                const std::string message = e.what();
                INFO(message.substr(0, 300));
                CHECK(message.rfind("deep.json:1:", 0) == 0);
                CHECK(message.find("nested more than 64 levels deep") != std::string::npos);
                CHECK(message.find('\n') == std::string::npos);
                CHECK(message.size() < 400);
            }
        }
    }
    // The pointer names where the limit was crossed: element 0 at depth 64.
    std::string pointer;
    for (std::size_t i = 1; i < wp::json::kMaxNesting; ++i)
        pointer += "/0";
    CHECK_THROWS_WITH(wp::json::parse(std::string(65, '[') + std::string(65, ']'), "a.json"),
                      Catch::Contains(": " + pointer + "/0: values nested more than 64"));
    // 64 levels are allowed.
    CHECK_NOTHROW(wp::json::parse(std::string(64, '[') + std::string(64, ']'), "a.json"));
}

TEST_CASE("loader: 10^5 materials load in linear time", "[scene][load]") {
    constexpr int kMaterials = 100000;
    std::string text = R"({"camera": )" + kCamera + R"(, "materials": {)";
    for (int i = 0; i < kMaterials; ++i) {
        text.append(i ? ", \"m" : "\"m").append(std::to_string(i));
        text.append(R"(": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]})");
    }
    text += R"(, "light": {"type": "emitter", "radiance": [1, 1, 1]}}, "shapes": [)" +
            triangle("m99999") + ", " + triangle("m0") + ", " + triangle("light") + "]}";
    // Processor time, not wall time: the test must not fail because other
    // processes share the machine (the loader is single-threaded).
    const std::clock_t start = std::clock();
    const wp::Scene scene = wp::parse_scene(text, "many.json");
    const double seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    REQUIRE(scene.materials.size() == kMaterials + 1);
    CHECK(scene.materials[12345].name == "m12345"); // the file's order
    CHECK(scene.triangles[0].material == 99999);
    CHECK(scene.triangles[2].material == kMaterials);
    // About 0.3 s when linear; the quadratic version took minutes.
    CHECK(seconds < 1.0 * wp::test::kTimeLimitScale);
}

TEST_CASE("loader: has_emitter tells a lit scene from a black one", "[scene][load]") {
    const std::string materials = R"({"white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
        "glow": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7], "emission": [1, 1, 1]},
        "light": {"type": "emitter", "radiance": [1, 1, 1]}})";
    auto load = [&](const std::string& shapes) {
        return wp::parse_scene(R"({"camera": )" + kCamera + R"(, "materials": )" + materials +
                                   R"(, "shapes": )" + shapes + "}",
                               "s.json");
    };
    auto list = [](const std::vector<std::string>& shapes) {
        std::string text = "[";
        for (const std::string& shape : shapes)
            text.append(text.size() > 1 ? ", " : "").append(shape);
        return text.append("]");
    };
    const std::string sphere =
        R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"})";
    CHECK_FALSE(wp::has_emitter(load(list({triangle("white")}))));
    // An emitter material that no shape uses gives no light either.
    CHECK_FALSE(wp::has_emitter(load(list({triangle("white"), sphere}))));
    CHECK(wp::has_emitter(load(list({triangle("white"), triangle("light")}))));
    CHECK(wp::has_emitter(load(list({triangle("glow")}))));
}
