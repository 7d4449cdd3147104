// Scene features and specialised kernels: the build options each scene
// gets, and that the specialised kernels (features switched off, primitive
// counts compiled in) render exactly what the general ones render.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>

#include "render/device_scene.hpp"
#include "scene/load.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

Scene hexroom(int size = 24) {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
    scene.camera.width = scene.camera.height = size;
    return scene;
}

std::uint32_t material_named(const Scene& scene, const std::string& name) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == name)
            return static_cast<std::uint32_t>(i);
    FAIL("no material " << name);
    return 0;
}

// The hexroom without its two spheres.
Scene triangles_only() {
    Scene scene = hexroom();
    scene.spheres.clear();
    return scene;
}

// The hexroom with both mirrors (wall and sphere) made diffuse.
Scene no_mirror() {
    Scene scene = hexroom();
    for (const char* name : {"front_right_wall", "mirror_sphere"})
        scene.materials[material_named(scene, name)].kind = MaterialKind::Diffuse;
    return scene;
}

// The hexroom without its area light; the red sphere glows instead: no
// triangle lights, and the sphere is a sphere light (next-event estimation
// samples it by its cone; without it, light arrives after every bounce).
Scene no_light() {
    Scene scene = hexroom();
    const std::uint32_t light = material_named(scene, "light");
    TriangleList unlit;
    for (const Triangle& t : scene.triangles)
        if (t.material != light)
            unlit.push_back(t);
    scene.triangles = std::move(unlit);
    scene.materials[material_named(scene, "red_sphere")].emission = glm::dvec3(20.0, 4.0, 2.0);
    return scene;
}

// Spheres only: a big ground sphere, a mirror sphere, a diffuse sphere and a
// glowing one (a sphere light), all seen from outside.
Scene spheres_only() {
    Scene scene;
    auto ground = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.7));
    auto mirror = test::add_material(scene, MaterialKind::Mirror, glm::dvec3(0.9));
    auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.8));
    auto glow = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5, 0.2, 0.1),
                                   glm::dvec3(5.0, 4.0, 3.0));
    scene.spheres.push_back({{0.0, 0.0, -1001.0}, 1000.0, ground});
    scene.spheres.push_back({{4.0, 1.5, 0.0}, 1.0, mirror});
    scene.spheres.push_back({{3.0, -1.5, -0.3}, 0.7, white});
    scene.spheres.push_back({{6.0, -0.5, 0.5}, 1.0, glow});
    scene.camera = test::make_camera({-3, 0, 0.5}, {4, 0, -0.3}, {0, 0, 1}, 60.0, 24, 24);
    return scene;
}

// More primitives than fixed counts allow: the hexroom plus a grid of small
// triangles, so the kernels keep the runtime-count loops.
Scene large() {
    Scene scene = hexroom();
    auto clutter = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    for (std::uint32_t i = 0;
         scene.triangles.size() + scene.spheres.size() <= kMaxFixedCountPrimitives; ++i) {
        glm::dvec3 c(1.0 + (i % 8), -3.0 + 0.8 * (i / 8 % 8), -2.0 + 0.5 * (i / 64));
        scene.triangles.push_back(
            {{c, c + glm::dvec3(0.3, 0, 0), c + glm::dvec3(0, 0.3, 0.1)}, clutter});
    }
    return scene;
}

// Every float of the two images, bit for bit.
bool same_bits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
           std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(a.rgb[0])) == 0;
}

double image_sum(const Image& image) {
    double sum = 0.0;
    for (auto v : image.rgb)
        sum += static_cast<double>(v);
    return sum;
}

void check_specialised_equals_general(const Scene& scene, bool nee = true) {
    IntegratorOptions specialised_options;
    specialised_options.next_event_estimation = nee;
    // One launch plan for both: on a CPU `auto` takes the wave plan for the
    // general kernels, whose float32 film batches end elsewhere
    // (tests/render/test_launch_plans.cpp compares the plans).
    specialised_options.launch_plan = LaunchPlan::Stages;
    IntegratorOptions general_options = specialised_options;
    general_options.general_kernels = true;

    test::Rendered specialised = test::render(scene, 4, 7, 0, specialised_options);
    test::Rendered general = test::render(scene, 4, 7, 0, general_options);

    Image a = specialised.film.mean(), b = general.film.mean();
    CHECK(image_sum(a) > 0.0); // not a trivially equal pair of black images
    CHECK(same_bits(a, b));
    CHECK(same_bits(specialised.film.variance_of_mean(), general.film.variance_of_mean()));
    CHECK(same_bits(specialised.film.half_mean(1), general.film.half_mean(1)));
    CHECK(specialised.stats.camera_rays == general.stats.camera_rays);
    CHECK(specialised.stats.bounce_rays == general.stats.bounce_rays);
    CHECK(specialised.stats.shadow_rays == general.stats.shadow_rays);
}

} // namespace

TEST_CASE("features: each scene's build options are exactly the expected ones") {
    CHECK(analyse_features(hexroom()).build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=0 -D WP_HAS_ROUGHCONDUCTOR=0 -D WP_HAS_DIELECTRIC=0 -D "
          "WP_HAS_THINDIELECTRIC=0 -D WP_HAS_PLASTIC=0 -D WP_HAS_ROUGHDIELECTRIC=0 -D "
          "WP_HAS_ROUGHPLASTIC=0 -D "
          "WP_HAS_SHADING_NORMALS=0 -D WP_HAS_ANISOTROPY=0 "
          "-D WP_HAS_LIGHTS=1 -D WP_HAS_POWER_LIGHT_PICK=0 -D WP_HAS_PLANAR_MIRRORS=1 -D "
          "WP_HAS_MIRROR_SPHERES=1 -D "
          "WP_HAS_LENS=0 -D WP_HAS_POINT_LIGHT=0 -D WP_HAS_SPOT_LIGHT=0 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=0 -D WP_HAS_CONSTANT_LIGHT=0 -D WP_HAS_ENVMAP_LIGHT=0 -D "
          "WP_HAS_SPHERE_LIGHT=0 -D WP_HAS_INSTANCES=0 -D "
          "WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0 -D WP_HAS_BITMAP_TEXTURE=0 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=0 -D "
          "WP_TRIANGLE_COUNT=26 -D "
          "WP_SPHERE_COUNT=2 -D WP_LIGHT_COUNT=2 -D "
          "WP_MIRROR_GROUP_TRIANGLES=2 -D WP_SHADOW_OCCLUDER_COUNT=5 -D "
          "WP_SHADOW_OCCLUDERS=21,22,23,24,25");
    CHECK(analyse_features(triangles_only()).build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=0 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=0 -D WP_HAS_ROUGHCONDUCTOR=0 -D WP_HAS_DIELECTRIC=0 -D "
          "WP_HAS_THINDIELECTRIC=0 -D WP_HAS_PLASTIC=0 -D WP_HAS_ROUGHDIELECTRIC=0 -D "
          "WP_HAS_ROUGHPLASTIC=0 -D "
          "WP_HAS_SHADING_NORMALS=0 -D WP_HAS_ANISOTROPY=0 "
          "-D WP_HAS_LIGHTS=1 -D WP_HAS_POWER_LIGHT_PICK=0 -D WP_HAS_PLANAR_MIRRORS=1 -D "
          "WP_HAS_MIRROR_SPHERES=0 -D "
          "WP_HAS_LENS=0 -D WP_HAS_POINT_LIGHT=0 -D WP_HAS_SPOT_LIGHT=0 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=0 -D WP_HAS_CONSTANT_LIGHT=0 -D WP_HAS_ENVMAP_LIGHT=0 -D "
          "WP_HAS_SPHERE_LIGHT=0 -D WP_HAS_INSTANCES=0 -D "
          "WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0 -D WP_HAS_BITMAP_TEXTURE=0 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=0 -D "
          "WP_TRIANGLE_COUNT=26 -D "
          "WP_SPHERE_COUNT=0 -D WP_LIGHT_COUNT=2 -D "
          "WP_MIRROR_GROUP_TRIANGLES=2 -D WP_SHADOW_OCCLUDER_COUNT=5 -D "
          "WP_SHADOW_OCCLUDERS=21,22,23,24,25");
    CHECK(analyse_features(spheres_only()).build_options() ==
          "-D WP_HAS_TRIANGLES=0 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=0 -D WP_HAS_ROUGHCONDUCTOR=0 -D WP_HAS_DIELECTRIC=0 -D "
          "WP_HAS_THINDIELECTRIC=0 -D WP_HAS_PLASTIC=0 -D WP_HAS_ROUGHDIELECTRIC=0 -D "
          "WP_HAS_ROUGHPLASTIC=0 -D "
          "WP_HAS_SHADING_NORMALS=0 -D WP_HAS_ANISOTROPY=0 "
          "-D WP_HAS_LIGHTS=0 -D WP_HAS_POWER_LIGHT_PICK=0 -D WP_HAS_PLANAR_MIRRORS=0 -D "
          "WP_HAS_MIRROR_SPHERES=0 -D "
          "WP_HAS_LENS=0 -D WP_HAS_POINT_LIGHT=0 -D WP_HAS_SPOT_LIGHT=0 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=0 -D WP_HAS_CONSTANT_LIGHT=0 -D WP_HAS_ENVMAP_LIGHT=0 -D "
          "WP_HAS_SPHERE_LIGHT=1 -D WP_HAS_INSTANCES=0 -D "
          "WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0 -D WP_HAS_BITMAP_TEXTURE=0 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=0 -D "
          "WP_TRIANGLE_COUNT=0 -D "
          "WP_SPHERE_COUNT=4 -D WP_LIGHT_COUNT=0 -D "
          "WP_MIRROR_GROUP_TRIANGLES=0");
    CHECK(analyse_features(no_mirror()).build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=0 -D "
          "WP_HAS_CONDUCTOR=0 -D WP_HAS_ROUGHCONDUCTOR=0 -D WP_HAS_DIELECTRIC=0 -D "
          "WP_HAS_THINDIELECTRIC=0 -D WP_HAS_PLASTIC=0 -D WP_HAS_ROUGHDIELECTRIC=0 -D "
          "WP_HAS_ROUGHPLASTIC=0 -D "
          "WP_HAS_SHADING_NORMALS=0 -D WP_HAS_ANISOTROPY=0 "
          "-D WP_HAS_LIGHTS=1 -D WP_HAS_POWER_LIGHT_PICK=0 -D WP_HAS_PLANAR_MIRRORS=0 -D "
          "WP_HAS_MIRROR_SPHERES=0 -D "
          "WP_HAS_LENS=0 -D WP_HAS_POINT_LIGHT=0 -D WP_HAS_SPOT_LIGHT=0 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=0 -D WP_HAS_CONSTANT_LIGHT=0 -D WP_HAS_ENVMAP_LIGHT=0 -D "
          "WP_HAS_SPHERE_LIGHT=0 -D WP_HAS_INSTANCES=0 -D "
          "WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0 -D WP_HAS_BITMAP_TEXTURE=0 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=0 -D "
          "WP_TRIANGLE_COUNT=26 -D "
          "WP_SPHERE_COUNT=2 -D WP_LIGHT_COUNT=2 -D "
          "WP_MIRROR_GROUP_TRIANGLES=0 -D WP_SHADOW_OCCLUDER_COUNT=5 -D "
          "WP_SHADOW_OCCLUDERS=21,22,23,24,25");
    CHECK(analyse_features(no_light()).build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=0 -D WP_HAS_ROUGHCONDUCTOR=0 -D WP_HAS_DIELECTRIC=0 -D "
          "WP_HAS_THINDIELECTRIC=0 -D WP_HAS_PLASTIC=0 -D WP_HAS_ROUGHDIELECTRIC=0 -D "
          "WP_HAS_ROUGHPLASTIC=0 -D "
          "WP_HAS_SHADING_NORMALS=0 -D WP_HAS_ANISOTROPY=0 "
          "-D WP_HAS_LIGHTS=0 -D WP_HAS_POWER_LIGHT_PICK=0 -D WP_HAS_PLANAR_MIRRORS=0 -D "
          "WP_HAS_MIRROR_SPHERES=0 -D "
          "WP_HAS_LENS=0 -D WP_HAS_POINT_LIGHT=0 -D WP_HAS_SPOT_LIGHT=0 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=0 -D WP_HAS_CONSTANT_LIGHT=0 -D WP_HAS_ENVMAP_LIGHT=0 -D "
          "WP_HAS_SPHERE_LIGHT=1 -D WP_HAS_INSTANCES=0 -D "
          "WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0 -D WP_HAS_BITMAP_TEXTURE=0 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=0 -D "
          "WP_TRIANGLE_COUNT=24 -D "
          "WP_SPHERE_COUNT=2 -D WP_LIGHT_COUNT=0 -D "
          "WP_MIRROR_GROUP_TRIANGLES=0");
    // Past the fixed-count limit: runtime counts and the hierarchy.
    CHECK(analyse_features(large()).build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=0 -D WP_HAS_ROUGHCONDUCTOR=0 -D WP_HAS_DIELECTRIC=0 -D "
          "WP_HAS_THINDIELECTRIC=0 -D WP_HAS_PLASTIC=0 -D WP_HAS_ROUGHDIELECTRIC=0 -D "
          "WP_HAS_ROUGHPLASTIC=0 -D "
          "WP_HAS_SHADING_NORMALS=0 -D WP_HAS_ANISOTROPY=0 "
          "-D WP_HAS_LIGHTS=1 -D WP_HAS_POWER_LIGHT_PICK=0 -D WP_HAS_PLANAR_MIRRORS=1 -D "
          "WP_HAS_MIRROR_SPHERES=1 -D "
          "WP_HAS_LENS=0 -D WP_HAS_POINT_LIGHT=0 -D WP_HAS_SPOT_LIGHT=0 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=0 -D WP_HAS_CONSTANT_LIGHT=0 -D WP_HAS_ENVMAP_LIGHT=0 -D "
          "WP_HAS_SPHERE_LIGHT=0 -D WP_HAS_INSTANCES=0 -D "
          "WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0 -D WP_HAS_BITMAP_TEXTURE=0 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=0 -D WP_USE_BVH=1");
    // The general kernels: every feature, runtime counts, the scene's hierarchy.
    CHECK(SceneFeatures::general_for(analyse_features(large())).build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=1 -D WP_HAS_ROUGHCONDUCTOR=1 -D WP_HAS_DIELECTRIC=1 -D "
          "WP_HAS_THINDIELECTRIC=1 -D WP_HAS_PLASTIC=1 -D WP_HAS_ROUGHDIELECTRIC=1 -D "
          "WP_HAS_ROUGHPLASTIC=1 -D "
          "WP_HAS_SHADING_NORMALS=1 -D WP_HAS_ANISOTROPY=1 "
          "-D WP_HAS_LIGHTS=1 -D WP_HAS_POWER_LIGHT_PICK=1 -D WP_HAS_PLANAR_MIRRORS=1 -D "
          "WP_HAS_MIRROR_SPHERES=1 -D "
          "WP_HAS_LENS=1 -D WP_HAS_POINT_LIGHT=1 -D WP_HAS_SPOT_LIGHT=1 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=1 -D WP_HAS_CONSTANT_LIGHT=1 -D WP_HAS_ENVMAP_LIGHT=1 -D "
          "WP_HAS_SPHERE_LIGHT=1 -D WP_HAS_INSTANCES=1 -D "
          "WP_HAS_TENT_FILTER=1 -D WP_HAS_GAUSSIAN_FILTER=1 -D WP_HAS_BITMAP_TEXTURE=1 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=1 -D WP_USE_BVH=1");
    CHECK(SceneFeatures::general_for(analyse_features(hexroom())).build_options() ==
          SceneFeatures::all().build_options());
    CHECK(SceneFeatures::all().build_options() ==
          "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=1 -D WP_HAS_DIFFUSE=1 -D WP_HAS_MIRROR=1 -D "
          "WP_HAS_CONDUCTOR=1 -D WP_HAS_ROUGHCONDUCTOR=1 -D WP_HAS_DIELECTRIC=1 -D "
          "WP_HAS_THINDIELECTRIC=1 -D WP_HAS_PLASTIC=1 -D WP_HAS_ROUGHDIELECTRIC=1 -D "
          "WP_HAS_ROUGHPLASTIC=1 -D "
          "WP_HAS_SHADING_NORMALS=1 -D WP_HAS_ANISOTROPY=1 "
          "-D WP_HAS_LIGHTS=1 -D WP_HAS_POWER_LIGHT_PICK=1 -D WP_HAS_PLANAR_MIRRORS=1 -D "
          "WP_HAS_MIRROR_SPHERES=1 -D "
          "WP_HAS_LENS=1 -D WP_HAS_POINT_LIGHT=1 -D WP_HAS_SPOT_LIGHT=1 -D "
          "WP_HAS_DIRECTIONAL_LIGHT=1 -D WP_HAS_CONSTANT_LIGHT=1 -D WP_HAS_ENVMAP_LIGHT=1 -D "
          "WP_HAS_SPHERE_LIGHT=1 -D WP_HAS_INSTANCES=1 -D "
          "WP_HAS_TENT_FILTER=1 -D WP_HAS_GAUSSIAN_FILTER=1 -D WP_HAS_BITMAP_TEXTURE=1 -D "
          "WP_HAS_CHECKERBOARD_TEXTURE=1");
}

TEST_CASE("features: fixed counts stop at the limit, and 0 turns them off") {
    Scene scene = hexroom();
    const std::uint32_t primitives =
        static_cast<std::uint32_t>(scene.triangles.size() + scene.spheres.size());
    CHECK(analyse_features(scene, primitives).fixed_counts);
    CHECK_FALSE(analyse_features(scene, primitives - 1).fixed_counts);
    CHECK_FALSE(analyse_features(scene, 0).fixed_counts);
    SceneFeatures runtime = analyse_features(scene, 0);
    CHECK(runtime.triangle_count == 0);
    CHECK(runtime.build_options().find("COUNT") == std::string::npos);
    CHECK(analyse_features(large()).fixed_counts == false);
}

TEST_CASE("features: describe() names the features and the compiled-in counts") {
    CHECK(analyse_features(hexroom()).describe() ==
          "triangles spheres diffuse mirror lights planar_mirrors mirror_spheres; counts 26+2; "
          "shadow tests 5 "
          "of 26 triangles");
    CHECK(analyse_features(spheres_only()).describe() ==
          "spheres diffuse mirror sphere_light; counts 0+4");
    CHECK(analyse_features(large()).describe() ==
          "triangles spheres diffuse mirror lights planar_mirrors mirror_spheres; bvh");
    CHECK(SceneFeatures::all().describe() ==
          "triangles spheres diffuse mirror conductor roughconductor dielectric thindielectric "
          "plastic roughdielectric roughplastic shading_normals anisotropy lights "
          "power_light_pick planar_mirrors mirror_spheres lens point_light spot_light "
          "directional_light "
          "constant_light envmap_light sphere_light instances tent_filter gaussian_filter "
          "bitmap_texture "
          "checkerboard_texture");
}

// The program's options begin with the features' (estimator options may follow).
bool starts_with_features(const std::string& options, const SceneFeatures& features) {
    const std::string expected = features.build_options();
    return options == expected || options.rfind(expected + " ", 0) == 0;
}

TEST_CASE("features: the integrator compiles the scene's options, or the general ones") {
    Scene scene = triangles_only();
    WavefrontIntegrator specialised(test::device(), scene, IntegratorOptions{});
    CHECK(starts_with_features(specialised.program().options, analyse_features(scene)));
    CHECK(specialised.features().build_options() == analyse_features(scene).build_options());
    IntegratorOptions general_options;
    general_options.general_kernels = true;
    WavefrontIntegrator general(test::device(), scene, general_options);
    CHECK(starts_with_features(general.program().options, SceneFeatures::all()));
}

TEST_CASE("features: specialised and general kernels render bit-identical images") {
    SECTION("hexroom") {
        check_specialised_equals_general(hexroom());
    }
    SECTION("triangles only") {
        check_specialised_equals_general(triangles_only());
    }
    SECTION("spheres only, next-event estimation on") {
        check_specialised_equals_general(spheres_only());
    }
    SECTION("spheres only, next-event estimation off") {
        check_specialised_equals_general(spheres_only(), false);
    }
    SECTION("no mirror") {
        check_specialised_equals_general(no_mirror());
    }
    SECTION("no light, next-event estimation on") {
        check_specialised_equals_general(no_light());
    }
    SECTION("no light, next-event estimation off") {
        check_specialised_equals_general(no_light(), false);
    }
    SECTION("more primitives than fixed counts allow") {
        check_specialised_equals_general(large());
    }
}

// The same for the features of lights, camera and materials, a test case of
// their own so that ctest runs the two halves side by side (each section
// builds its programs, most of this test's time when the cache is cold).
TEST_CASE("features: specialised and general kernels render bit-identical images: lens, "
          "filters, emitters, anisotropy") {
    // The camera's switches: the lens and a filter compiled in alone, and
    // chosen at run time among all of them.
    SECTION("a thin lens and the tent filter") {
        Scene scene = hexroom();
        scene.camera.aperture_radius = 0.05;
        scene.camera.focus_distance = 3.0;
        scene.camera.filter = FilterKind::Tent;
        check_specialised_equals_general(scene);
    }
    SECTION("the Gaussian filter") {
        Scene scene = hexroom();
        scene.camera.filter = FilterKind::Gaussian;
        check_specialised_equals_general(scene);
    }
    // The emitters: each kind's switch alone, and all of them chosen among
    // at run time, beside the hexroom's emissive triangles.
    SECTION("a spot and a sun beside the area lights") {
        Scene scene = hexroom();
        Emitter spot;
        spot.kind = EmitterKind::Spot;
        spot.position = {0.5, 0.2, 1.0};
        spot.direction = {0, 0, -1};
        spot.value = glm::dvec3(2.0);
        scene.emitters.push_back(spot);
        Emitter sun;
        sun.kind = EmitterKind::Directional;
        sun.direction = glm::normalize(glm::dvec3(1, 1, -2));
        scene.emitters.push_back(sun);
        check_specialised_equals_general(scene);
    }
    // The tangent frame (WP_HAS_ANISOTROPY): the mirror wall's triangles
    // (no texture coordinates) and the mirror sphere turned anisotropic, and
    // the isotropic rough kinds beside them keep wp_make_basis either way.
    SECTION("anisotropic rough conductors") {
        Scene scene = hexroom();
        for (Material& m : scene.materials)
            if (m.kind == MaterialKind::Mirror) {
                m.kind = MaterialKind::RoughConductor;
                m.alpha_u = 0.05;
                m.alpha_v = 0.3;
            }
        REQUIRE(analyse_features(scene).anisotropy);
        check_specialised_equals_general(scene);
    }
    // The power light pick (its emission.w read in both), and next-event
    // estimation through the mirror wall and sphere beside a sphere light.
    SECTION("unequal area lights picked by power, mirrors beside a sphere light") {
        Scene scene = hexroom();
        auto bright = test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0),
                                         glm::dvec3(400, 300, 200));
        Triangle light = scene.triangles.back(); // the light's second triangle
        light.material = bright;
        scene.triangles.set(scene.triangles.size() - 1, light);
        scene.spheres.push_back({{0.5, 0.3, -0.4}, 0.1, bright});
        const SceneFeatures f = analyse_features(scene);
        REQUIRE(f.power_light_pick);
        REQUIRE(f.sphere_light);
        REQUIRE(f.planar_mirrors);
        check_specialised_equals_general(scene);
    }
    SECTION("a point light and a constant sky, no area light") {
        Scene scene = no_light();
        Emitter point;
        point.kind = EmitterKind::Point;
        point.position = {0.5, 0.2, 1.0};
        scene.emitters.push_back(point);
        Emitter sky;
        sky.kind = EmitterKind::Constant;
        sky.value = glm::dvec3(0.2, 0.3, 0.4);
        scene.emitters.push_back(sky);
        check_specialised_equals_general(scene);
    }
}

TEST_CASE("features: the hierarchy and the loop over every primitive render the same image",
          "[statistical]") {
    for (const auto& [name, scene] :
         {std::pair<std::string, Scene>{"hexroom", hexroom()}, {"large", large()}}) {
        INFO(name);
        IntegratorOptions bvh, loop;
        bvh.launch_plan = loop.launch_plan = LaunchPlan::Stages; // as above: one plan for both
        bvh.traversal = Traversal::Hierarchy;
        loop.traversal = Traversal::Loop;
        test::Rendered a = test::render(scene, 8, 3, 0, bvh);
        test::Rendered b = test::render(scene, 8, 3, 0, loop);
        // Both find the same hit at the same t, except where two primitives
        // are hit at the same distance (a ray through a shared edge), which
        // may pick the other triangle of a wall: a pixel or two at most.
        const Image ma = a.film.mean(), mb = b.film.mean();
        std::size_t differing = 0;
        for (std::size_t p = 0; p < ma.rgb.size(); p += 3)
            differing += std::memcmp(&ma.rgb[p], &mb.rgb[p], 3 * sizeof(ma.rgb[0])) != 0;
        WARN(name << ": " << differing << " of " << ma.rgb.size() / 3
                  << " pixels differ between the hierarchy and the loop");
        CHECK(differing * 100 <= ma.rgb.size() / 3);
        CHECK(image_sum(ma) > 0.0);
        for (int c = 0; c < 3; ++c) {
            const test::MeanWithError ea = test::image_mean(a.film, c),
                                      eb = test::image_mean(b.film, c);
            CHECK(std::fabs(ea.mean - eb.mean) <=
                  5.0 * std::hypot(ea.standard_error, eb.standard_error));
        }
        CHECK(a.stats.camera_rays == b.stats.camera_rays);
    }
}

TEST_CASE("features: anisotropy is on only for alpha_u != alpha_v on a rough kind in use") {
    Scene scene = hexroom();
    CHECK_FALSE(analyse_features(scene).anisotropy);
    Material& m = scene.materials[scene.spheres[0].material];
    m.kind = MaterialKind::RoughConductor;
    m.alpha_u = m.alpha_v = 0.2;
    CHECK_FALSE(analyse_features(scene).anisotropy);
    m.alpha_v = 0.3;
    CHECK(analyse_features(scene).anisotropy);
    // Textured roughness: the constants no longer count, the textures do.
    m.alpha_u_texture = m.alpha_v_texture = 1;
    CHECK_FALSE(analyse_features(scene).anisotropy);
    m.alpha_v_texture = 2;
    CHECK(analyse_features(scene).anisotropy);
    m.alpha_v_texture = 0;
    CHECK(analyse_features(scene).anisotropy);
    // Diffuse and rough plastic have no alpha_u/alpha_v of their own.
    m.kind = MaterialKind::RoughPlastic;
    CHECK_FALSE(analyse_features(scene).anisotropy);
}
