// Scenes that wavepath did not write: mitsuba-data's, committed unchanged
// under tests/data/third-party/mitsuba-data (its README says which and
// whence). Each is read as it is and rendered small: it loads, renders
// finite, and looks like itself (the Cornell box's red wall on the left of
// the image, its green one on the right). How close each comes to Mitsuba
// 3's own image is the agreement test's business
// (tests/render/test_mitsuba_agreement.cpp, the Cornell box) and the
// gallery's (docs/gallery.md, all of them).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "scene/load.hpp"
#include "support/render_helpers.hpp"

using namespace wp;
using namespace wp::test;

namespace {

const std::string kScenes =
    std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/third-party/mitsuba-data/scenes/";

// A render's mean per channel over the columns [x0, x1), every value finite.
glm::dvec3 columns_mean(const Image& image, int x0, int x1) {
    glm::dvec3 sum(0.0);
    for (int y = 0; y < image.height; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = image.pixel(x, y)[c];
                REQUIRE(std::isfinite(v));
                sum[c] += v;
            }
    return sum / double(image.height * (x1 - x0));
}

Image render_small(Scene scene, int width, int height, std::uint32_t spp) {
    scene.camera.width = width;
    scene.camera.height = height;
    const Rendered r = render(scene, spp, 3);
    CHECK(r.stats.nonfinite_samples == 0);
    return r.film.mean();
}

// The Cornell box, however it is put together: lit, red on the left, green
// on the right (Mitsuba's camera sees +x on the image's left). The light is
// warm (cbox-rgb.xml's is 18.4, 11.0, 2.75), so the green wall is greener
// than red by less than the red wall is redder than green.
void check_cornell_box(const std::string& file) {
    INFO(file);
    SceneReadOptions options;
    options.defines = {{"res", "32"}};
    const Scene scene = load_scene(kScenes + "cbox/" + file, options);
    CHECK(scene.camera.width == 32);
    CHECK(scene.materials.size() == 5); // box, white, red, green, and the light's, emitting
    const Image image = render_small(scene, 32, 32, 16);
    const glm::dvec3 left = columns_mean(image, 0, 4), right = columns_mean(image, 28, 32);
    const glm::dvec3 all = columns_mean(image, 0, 32);
    INFO("left " << left.x << " " << left.y << " " << left.z << ", right " << right.x << " "
                 << right.y << " " << right.z);
    CHECK(left.x > 2.0 * left.y);
    CHECK(right.y > 1.2 * right.x);
    CHECK(all.y > 0.1);
    CHECK(all.y < 2.0);
}

} // namespace

TEST_CASE("third-party scenes: mitsuba-data's Cornell boxes load unchanged and render",
          "[render][mitsuba][third-party]") {
    check_cornell_box("cbox.xml");          // spectra as wavelength:value pairs
    check_cornell_box("cbox-rgb.xml");      // includes, a forward <ref> to a top-level area emitter
    check_cornell_box("cbox-spectral.xml"); // the same with spectra
}

TEST_CASE("third-party scenes: mitsuba-data's matpreview loads unchanged and renders",
          "[render][mitsuba][third-party]") {
    // serialized meshes, an envmap turned by a rotate and a matrix, a
    // checkerboard by <ref>, plastic.
    SceneReadOptions options;
    options.defines = {{"width", "32"}, {"height", "24"}};
    const Scene scene = load_scene(kScenes + "matpreview/matpreview.xml", options);
    CHECK(scene.triangles.size() > 1000);
    const glm::dvec3 all = columns_mean(render_small(scene, 32, 24, 8), 0, 32);
    CHECK(all.x > 0.05);
    CHECK(all.x < 10.0);
}

TEST_CASE("third-party scenes: mitsuba-data's hello.xml: the direct integrator refused, "
          "rendered with --lenient",
          "[render][mitsuba][third-party]") {
    const std::string path = kScenes + "hello.xml";
    try {
        (void)load_scene(path);
        FAIL("hello.xml loaded without --lenient");
    } catch (const SceneError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find("<integrator type=\"direct\">: unsupported integrator 'direct'") !=
              std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
    SceneReadOptions options;
    options.lenient = true;
    const Scene scene = load_scene(path, options); // teapot.ply through <path value="../common"/>
    CHECK(scene.emitters.size() == 2);             // the two point lights
    CHECK(scene.triangles.size() > 1000);
    CHECK(scene.camera.width == 1024);
    const glm::dvec3 all = columns_mean(render_small(scene, 32, 24, 8), 0, 32);
    CHECK(all.x > all.z); // a yellow teapot
    CHECK(all.x > 0.0);
}
