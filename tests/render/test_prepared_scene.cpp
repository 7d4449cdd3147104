// The prepared scene (render/prepared_scene.hpp): made once, it is what a
// render's devices upload; the preparation that frees the scene's triangles
// on the way gives the same arrays, and the images stay the same.
#include <catch2/catch.hpp>

#include <cstring>
#include <vector>

#include "render/prepared_scene.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

template <typename T, typename Allocator>
bool same_bytes(const std::vector<T, Allocator>& a, const std::vector<T, Allocator>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

} // namespace

TEST_CASE("prepared scene: freeing the triangles once flattened gives the same arrays") {
    // The Cornell bunny (69,451 + 18 triangles) has its hierarchy by size;
    // the hexroom is given one, and has planar mirrors and mirror spheres.
    for (const char* name : {"cornell-bunny", "hexroom"}) {
        INFO(name);
        const Scene scene =
            load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/" + name + ".json");
        IntegratorOptions options;
        options.traversal = Traversal::Hierarchy;
        const std::uint64_t before = scene_hierarchies_built();
        const PreparedScene kept = prepare_scene(scene, options);
        Scene released_scene = scene;
        const PreparedScene released = prepare_scene_releasing_triangles(released_scene, options);
        CHECK(scene_hierarchies_built() == before + 2);

        CHECK(released_scene.triangles.empty());
        CHECK(released_scene.triangles.heap_bytes() == 0);
        CHECK(released_scene.materials.size() == scene.materials.size());
        CHECK(released_scene.camera.width == scene.camera.width);

        const DeviceScene& a = *kept.device_scene;
        const DeviceScene& b = *released.device_scene;
        REQUIRE(a.triangles.size() == scene.triangles.size());
        CHECK(!a.bvh_nodes.empty());
        CHECK(same_bytes(a.triangles, b.triangles));
        CHECK(same_bytes(a.bvh_nodes, b.bvh_nodes));
        CHECK(same_bytes(a.spheres, b.spheres));
        CHECK(same_bytes(a.lights, b.lights));
        CHECK(same_bytes(a.mirror_spheres, b.mirror_spheres));
        CHECK(same_bytes(a.mirror_triangles, b.mirror_triangles));
        CHECK(same_bytes(a.triangle_normals, b.triangle_normals));
        CHECK(kept.features.describe() == released.features.describe());
        CHECK(kept.width == scene.camera.width);
        CHECK(kept.height == scene.camera.height);
    }
}

TEST_CASE("prepared scene: an integrator of a prepared scene renders the image of the scene") {
    const Scene scene = test::hexroom(20, 16);
    IntegratorOptions options;
    options.seed = 4;
    const test::Rendered direct = test::render(scene, 4, 4, 0, options);
    const PreparedScene prepared = prepare_scene(scene, options);
    WavefrontIntegrator integrator(test::device(), prepared);
    CHECK(integrator.width() == 20);
    CHECK(integrator.height() == 16);
    Film film(20, 16);
    integrator.render(0, 4, film);
    const Image a = film.mean(), b = direct.film.mean();
    REQUIRE(a.rgb.size() == b.rgb.size());
    CHECK(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0);
}

TEST_CASE("prepared scene: a Mitsuba file's max_depth and rr_depth, unless the command line "
          "gives its own") {
    Scene scene = test::hexroom(4, 4);
    // A JSON scene: wavepath's bounce cap, as the options say.
    IntegratorOptions options;
    options.max_depth = 7;
    options.max_depth_given = true;
    CHECK(prepare_scene(scene, options).options.depth_rule == DepthRule::Bounces);
    CHECK(prepare_scene(scene, options).options.max_depth == 7);
    // A Mitsuba file's: its max_depth counts edges, its rr_depth is the
    // roulette depth ...
    scene.mitsuba_depths = true;
    scene.max_depth = 3;
    scene.rr_depth = 5;
    const IntegratorOptions file = prepare_scene(scene, IntegratorOptions{}).options;
    CHECK(file.depth_rule == DepthRule::PathLength);
    CHECK(file.max_depth == 3);
    CHECK(file.roulette_depth == 5);
    // ... unless the command line gives them: --max-depth then counts edges
    // as the file's would, --roulette-depth is wavepath's.
    options.roulette_depth = 2;
    options.roulette_depth_given = true;
    const IntegratorOptions given = prepare_scene(scene, options).options;
    CHECK(given.depth_rule == DepthRule::PathLength);
    CHECK(given.max_depth == 7);
    CHECK(given.roulette_depth == 2);
    // Mitsuba's -1 (no limit) is wavepath's default, the safety cap.
    scene.max_depth = -1;
    scene.rr_depth = 0;
    const IntegratorOptions unlimited = prepare_scene(scene, IntegratorOptions{}).options;
    CHECK(unlimited.depth_rule == DepthRule::Bounces);
    CHECK(unlimited.max_depth == IntegratorOptions{}.max_depth);
    CHECK(unlimited.roulette_depth == IntegratorOptions{}.roulette_depth);
    CHECK(describe_estimator(file).find("+path-length-3") != std::string::npos);
}
