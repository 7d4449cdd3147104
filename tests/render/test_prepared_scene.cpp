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

template <typename T> bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
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
        CHECK(released_scene.triangles.capacity() == 0);
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
