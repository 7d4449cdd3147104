// Shadow culling (render/shadow_occluders.hpp): which triangles the shadow
// stage may skip, and that skipping them changes no image where the
// segments' rounding is not at stake.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "render/device_scene.hpp"
#include "render/shadow_occluders.hpp"
#include "scene/load.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

std::vector<std::uint32_t> all_but(const Scene& scene, const std::vector<std::uint32_t>& culled) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t i = 0; i < scene.triangles.size(); ++i)
        if (std::find(culled.begin(), culled.end(), i) == culled.end())
            out.push_back(i);
    return out;
}

// A closed box [0,4]^3 seen from inside: every face bounds the scene.
Scene closed_box() {
    Scene scene;
    auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.7));
    test::add_box_inward(scene, glm::dvec3(0.0), glm::dvec3(4.0), white);
    scene.camera = test::make_camera({2, 1, 2}, {2, 3, 2}, {0, 0, 1}, 60.0, 8, 8);
    return scene;
}

bool same_bits(const Image& a, const Image& b) {
    return a.rgb.size() == b.rgb.size() &&
           std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(a.rgb[0])) == 0;
}

} // namespace

TEST_CASE("shadow culling: the hexroom's bounding faces are its walls, floor, ceiling and the "
          "tetrahedron's base") {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
    // Expected from the scene's own description: the room's materials, and
    // the tetrahedron's face that lies on the floor (z = -5); not the
    // tetrahedron's other faces nor the light just under the ceiling.
    std::vector<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        const std::string& material = scene.materials[t.material].name;
        const bool room = material.find("wall") != std::string::npos || material == "floor" ||
                          material == "ceiling";
        const bool on_floor =
            std::all_of(t.v.begin(), t.v.end(), [](const glm::dvec3& v) { return v.z == -5.0; });
        if (!room && !on_floor)
            expected.push_back(i);
    }
    CHECK(expected.size() == 5); // 3 tetrahedron faces and the light's 2 triangles
    CHECK(shadow_occluders(scene) == expected);

    const SceneFeatures features = analyse_features(scene);
    CHECK(features.shadow_culling);
    CHECK(features.shadow_occluders == expected);
}

TEST_CASE("shadow culling: a face stops bounding the scene when anything or the eye crosses its "
          "plane") {
    Scene box = closed_box();
    CHECK(shadow_occluders(box).empty());
    // Features: nothing to test at all, so the count is 0 and the list absent.
    CHECK(analyse_features(box).build_options().find("-D WP_SHADOW_OCCLUDER_COUNT=0") !=
          std::string::npos);
    CHECK(analyse_features(box).build_options().find("WP_SHADOW_OCCLUDERS=") == std::string::npos);

    SECTION("a triangle through the floor") {
        Scene scene = box;
        auto grey = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
        scene.triangles.push_back(
            {{glm::dvec3(1, 1, -0.5), glm::dvec3(2, 1, 1), glm::dvec3(1, 2, 1)}, grey});
        // The floor (triangles 0 and 1) and the new triangle itself, which is
        // no bounding face: the box lies on both sides of its plane.
        CHECK(shadow_occluders(scene) == std::vector<std::uint32_t>{0, 1, 12});
    }
    SECTION("a sphere through the ceiling") {
        Scene scene = box;
        scene.spheres.push_back({glm::dvec3(2, 2, 3.9), 0.5, 0});
        CHECK(shadow_occluders(scene) == std::vector<std::uint32_t>{2, 3});
    }
    SECTION("a sphere touching the ceiling from inside still leaves it a bounding face") {
        Scene scene = box;
        scene.spheres.push_back({glm::dvec3(2, 2, 3.5), 0.5, 0});
        CHECK(shadow_occluders(scene).empty());
    }
    SECTION("the eye outside the x = 4 wall") {
        Scene scene = box;
        scene.camera = test::make_camera({5, 2, 2}, {2, 2, 2}, {0, 0, 1}, 60.0, 8, 8);
        CHECK(shadow_occluders(scene) == std::vector<std::uint32_t>{6, 7});
    }
    SECTION("the eye in the floor's plane") {
        Scene scene = box;
        scene.camera = test::make_camera({2, 2, 0}, {2, 3, 1}, {0, 0, 1}, 60.0, 8, 8);
        CHECK(shadow_occluders(scene) == std::vector<std::uint32_t>{0, 1});
    }
    SECTION("vertex normals: every triangle is kept") {
        Scene scene = box;
        Triangle smooth = scene.triangles[5];
        smooth.has_normals = true;
        smooth.normals = {glm::dvec3(0, 0, -1), glm::dvec3(0, 0, -1), glm::dvec3(0, 0, -1)};
        scene.triangles.set(5, smooth);
        CHECK(shadow_occluders(scene) == all_but(scene, {}));
        CHECK_FALSE(analyse_features(scene).shadow_culling);
    }
}

TEST_CASE("shadow culling: the hexroom renders bit-identically with and without it, in every "
          "launch plan") {
    const Scene scene = test::hexroom(24, 24);
    for (LaunchPlan plan : {LaunchPlan::Stages, LaunchPlan::Bounce, LaunchPlan::Wave}) {
        IntegratorOptions culled;
        culled.launch_plan = plan;
        IntegratorOptions all_faces = culled;
        all_faces.shadow_culling = false;
        test::Rendered a = test::render(scene, 4, 11, 0, culled);
        test::Rendered b = test::render(scene, 4, 11, 0, all_faces);
        INFO("launch plan " << static_cast<int>(plan));
        CHECK(a.stats.shadow_rays > 0);
        CHECK(same_bits(a.film.mean(), b.film.mean()));
        CHECK(same_bits(a.film.variance_of_mean(), b.film.variance_of_mean()));
        CHECK(a.stats.shadow_rays == b.stats.shadow_rays);
    }
}

TEST_CASE("shadow culling: the option turns it off in the kernels' build options") {
    const Scene scene = test::hexroom(8, 8);
    IntegratorOptions off;
    off.shadow_culling = false;
    WavefrontIntegrator with(test::device(), scene, IntegratorOptions{});
    WavefrontIntegrator without(test::device(), scene, off);
    CHECK(with.features().build_options().find("WP_SHADOW_OCCLUDERS=21,22,23,24,25") !=
          std::string::npos);
    CHECK(without.features().build_options().find("WP_SHADOW_OCCLUDER") == std::string::npos);
}

// Stability case 9's scene: a sphere of radius 1e-3 lit by a 2x2 light 1e3
// away. Its shadow rays are a million times longer than the light's
// coordinates; each must stop short of the light's plane by more than the
// rounding of its own length, or the light's second triangle shadows its
// first (the centre pixels came out 10-20 % dark before the margin grew with
// the length). A point of the sphere's front whose normal is tilted by
// asin(s) from the axis reads rho / pi * L A / d^2 * sqrt(1 - s^2); a pixel,
// that averaged over its area (the light's size changes it by under 1e-5).
TEST_CASE("shadow rays 1e3 long reach a light of size 2: the far small sphere is lit as "
          "computed, with and without culling",
          "[statistical]") {
    Scene scene =
        load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/stress/sphere-far-small.json");
    const int size = 16;
    scene.camera.width = scene.camera.height = size;
    const double radius = 1e-3, centre = 1000.0, distance = centre - radius + 1.0;
    const double lit = 0.8 / M_PI * 5.0 * 4.0 / (distance * distance);
    // The image plane's pixel at the sphere's distance, in units of its radius.
    const double pixel =
        2.0 * centre * std::tan(scene.camera.vertical_fov_degrees * M_PI / 360.0) / size / radius;
    auto expected = [&](int x, int y) {
        const int n = 64;
        double sum = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double u = (x + (i + 0.5) / n - 0.5 * size) * pixel;
                const double v = (y + (j + 0.5) / n - 0.5 * size) * pixel;
                sum += std::sqrt(std::max(0.0, 1.0 - u * u - v * v));
            }
        return lit * sum / (n * n);
    };
    for (bool culling : {true, false}) {
        IntegratorOptions options;
        options.shadow_culling = culling;
        options.general_kernels = !culling; // the general kernels never cull
        test::Rendered r = test::render(scene, 64, 3, 0, options);
        Image mean = r.film.mean(), variance = r.film.variance_of_mean();
        for (int y = 6; y <= 9; ++y)
            for (int x = 6; x <= 9; ++x) {
                const std::size_t i = 3 * (static_cast<std::size_t>(y) * size + x);
                const double value = mean.rgb[i], sigma = std::sqrt(variance.rgb[i]);
                const double want = expected(x, y);
                INFO("culling " << culling << ", pixel " << x << "," << y << ": " << value << " +- "
                                << sigma << ", expected " << want);
                CHECK(std::abs(value - want) <= 1e-3 * want + 5.0 * sigma);
            }
    }
}
