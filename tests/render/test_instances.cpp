// Instanced scenes render what the same geometry flattened into plain
// triangles renders: a box lit from its ceiling holding smooth (vertex
// normals) diffuse and glass balls placed by scaled, rotated and mirrored
// instances. A mirrored instance keeps its front on its object normals' side
// (kernels/instance.h), so the glass must bend light the same way in both;
// the flattened copy reverses a mirrored triangle's winding to match
// (tests/support/instancing.hpp). Both render with the same seed, and every
// 8x8 block's mean must agree within 5 standard errors. Then instanced
// mirrors beside a planar mirror, against next-event estimation through
// their flattened copies.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>

#include "render/device_scene.hpp"
#include "scene/transform.hpp"
#include "support/instancing.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

// A ball of `rings` x 2 `rings` quads with its vertex normals (smooth).
ShapeGroup ball(const std::string& name, std::uint32_t material, int rings) {
    ShapeGroup group{name, {}};
    auto at = [&](int i, int j) {
        const double theta = M_PI * i / rings, phi = M_PI * j / rings;
        return glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta));
    };
    auto add = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
        Triangle t{{a, b, c}, material};
        t.has_normals = true;
        t.normals = {a, b, c}; // unit: points of the unit sphere
        if (glm::length(glm::cross(b - a, c - a)) > 1e-9)
            group.triangles.push_back(t);
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < 2 * rings; ++j) { // outward winding
            add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return group;
}

Scene instanced_box() {
    Scene scene;
    scene.camera = test::make_camera({0.5, 0.05, 0.5}, {0.5, 1, 0.45}, {0, 0, 1}, 60.0, 48, 48);
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.7));
    const auto red = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.7, 0.2, 0.1));
    const auto glass = test::add_material(scene, MaterialKind::Dielectric, glm::dvec3(1.0));
    const auto light =
        test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(8.0));
    test::add_box_inward(scene, glm::dvec3(0.0), glm::dvec3(1.0), white);
    test::add_quad(scene, {0.4, 0.4, 0.999}, {0.4, 0.6, 0.999}, {0.6, 0.6, 0.999},
                   {0.6, 0.4, 0.999}, light);
    scene.shape_groups = {ball("diffuse ball", red, 6), ball("glass ball", glass, 6)};
    std::mt19937 generator(7);
    for (int k = 0; k < 6; ++k) {
        const glm::dmat4 placement =
            test::random_placement(generator, k % 2 == 1, {0.3, 0.45, 0.3}, {0.7, 0.8, 0.6});
        const Transform shrink = Transform::scale(0.12);
        scene.instances.push_back({static_cast<std::uint32_t>(k % 2), placement * shrink.matrix()});
    }
    return scene;
}

} // namespace

TEST_CASE("instances: an instanced scene renders the image of its flattened copy within noise",
          "[render][instances]") {
    const Scene instanced = instanced_box();
    const Scene flat = test::flattened_copy(instanced);
    REQUIRE(analyse_features(instanced).instances);
    REQUIRE_FALSE(analyse_features(flat).instances);
    const test::Rendered a = test::render(instanced, 32, 11);
    const test::Rendered b = test::render(flat, 32, 11);
    const Image mean_a = a.film.mean(), mean_b = b.film.mean();
    const Image var_a = a.film.variance_of_mean(), var_b = b.film.variance_of_mean();
    const int block = 8, w = instanced.camera.width, h = instanced.camera.height;
    double worst = 0.0, total_a = 0.0;
    for (int by = 0; by < h / block; ++by)
        for (int bx = 0; bx < w / block; ++bx)
            for (int c = 0; c < 3; ++c) {
                double sa = 0, sb = 0, va = 0, vb = 0;
                for (int y = by * block; y < (by + 1) * block; ++y)
                    for (int x = bx * block; x < (bx + 1) * block; ++x) {
                        const std::size_t i = (std::size_t(y) * w + x) * 3 + c;
                        sa += mean_a.rgb[i];
                        sb += mean_b.rgb[i];
                        va += var_a.rgb[i];
                        vb += var_b.rgb[i];
                    }
                total_a += sa;
                const double sigma = std::sqrt(va + vb);
                const double apart = std::fabs(sa - sb) / (sigma > 0 ? sigma : 1e-30);
                INFO("block " << bx << "," << by << " channel " << c << ": " << sa << " vs " << sb);
                CHECK(apart < 5.0);
                worst = std::max(worst, apart);
            }
    CHECK(total_a > 0.0);
    WARN("instanced against flattened: the worst 8x8 block is " << worst << " sigma apart");
}

TEST_CASE("instances: textures and anisotropic highlights on instances follow their world-space "
          "texture coordinates and tangents, as on their flattened copies",
          "[render][instances]") {
    // Tiles with texture coordinates: a checkerboard diffuse one and an
    // anisotropic rough metal one (alpha_u along dp/du), placed turned,
    // stretched and mirrored; the same seed for both renders.
    Scene scene;
    scene.camera = test::make_camera({0.5, 0.05, 0.5}, {0.5, 1, 0.45}, {0, 0, 1}, 60.0, 48, 48);
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.7));
    const auto light =
        test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(8.0));
    Texture checks;
    checks.to_u = glm::dvec3(4.0, 0.0, 0.0); // squares twice as many along u as v:
    checks.to_v = glm::dvec3(0.0, 2.0, 0.0); // not the same with u and v swapped
    checks.color0 = glm::dvec3(0.8, 0.3, 0.1);
    checks.color1 = glm::dvec3(0.1, 0.3, 0.8);
    scene.textures.push_back(checks);
    const auto checkered = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    scene.materials[checkered].reflectance_texture = 1;
    const auto brushed = test::add_material(scene, MaterialKind::RoughConductor, glm::dvec3(0.9));
    scene.materials[brushed].alpha_u = 0.03;
    scene.materials[brushed].alpha_v = 0.4;
    test::add_box_inward(scene, glm::dvec3(0.0), glm::dvec3(1.0), white);
    test::add_quad(scene, {0.4, 0.4, 0.999}, {0.4, 0.6, 0.999}, {0.6, 0.6, 0.999},
                   {0.6, 0.4, 0.999}, light);
    auto tile = [](std::uint32_t material, double x) {
        TriangleList out;
        const glm::dvec3 p[4] = {{x - 1, -1, 0}, {x + 1, -1, 0}, {x + 1, 1, 0}, {x - 1, 1, 0}};
        const glm::dvec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (const auto& [a, b, c] : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
            Triangle t{{p[a], p[b], p[c]}, material};
            t.has_uvs = true;
            t.uvs = {uv[a], uv[b], uv[c]};
            out.push_back(t);
        }
        return out;
    };
    ShapeGroup group{"tiles", tile(checkered, -1.1)};
    for (const Triangle& t : tile(brushed, 1.1))
        group.triangles.push_back(t);
    scene.shape_groups = {group};
    const Transform placements[3][3] = {
        {Transform::scale(glm::dvec3(0.12, 0.15, 0.1)), Transform::rotate(-70, {1, 0, 0}),
         Transform::translate({0.5, 0.75, 0.5})},
        {Transform::scale(glm::dvec3(-0.1, 0.12, 0.1)), Transform::rotate(-20, {1, 0.2, 0.3}),
         Transform::translate({0.45, 0.6, 0.15})},
        {Transform::scale(0.09), Transform::rotate(60, {0, 1, 0}),
         Transform::translate({0.35, 0.5, 0.75})}};
    for (const auto& steps : placements)
        scene.instances.push_back({0, Transform::compose(steps).matrix()});
    const Scene flat = test::flattened_copy(scene);
    REQUIRE(analyse_features(scene).anisotropy);
    REQUIRE(analyse_features(scene).checkerboard_texture);

    const test::Rendered a = test::render(scene, 32, 5);
    const test::Rendered b = test::render(flat, 32, 5);
    const Image mean_a = a.film.mean(), mean_b = b.film.mean();
    const Image var_a = a.film.variance_of_mean(), var_b = b.film.variance_of_mean();
    double worst = 0.0;
    for (int by = 0; by < 6; ++by)
        for (int bx = 0; bx < 6; ++bx)
            for (int c = 0; c < 3; ++c) {
                double sa = 0, sb = 0, va = 0, vb = 0;
                for (int y = by * 8; y < by * 8 + 8; ++y)
                    for (int x = bx * 8; x < bx * 8 + 8; ++x) {
                        const std::size_t i = (std::size_t(y) * 48 + x) * 3 + c;
                        sa += mean_a.rgb[i];
                        sb += mean_b.rgb[i];
                        va += var_a.rgb[i];
                        vb += var_b.rgb[i];
                    }
                const double apart = std::fabs(sa - sb) / std::sqrt(va + vb);
                INFO("block " << bx << "," << by << " channel " << c);
                CHECK(apart < 5.0);
                worst = std::max(worst, apart);
            }
    // And pixel by pixel, which a texture's detail needs (a checker square
    // is half a block wide): with the same seed the renders follow the same
    // paths, so no pixel may stray 5 of its standard errors.
    int far_pixels = 0;
    for (std::size_t i = 0; i < mean_a.rgb.size(); ++i) {
        const double sigma = std::sqrt(double(var_a.rgb[i]) + double(var_b.rgb[i]));
        far_pixels += std::fabs(double(mean_a.rgb[i]) - double(mean_b.rgb[i])) >
                      5.0 * sigma + 1e-6 * std::fabs(double(mean_b.rgb[i]));
    }
    CHECK(far_pixels == 0);
    WARN("textured and anisotropic instances against flattened: the worst 8x8 block is "
         << worst << " sigma apart, " << far_pixels << " pixels past 5 sigma");
}

TEST_CASE("instances: the scene's specialised kernels and the general ones render the same bits",
          "[render][instances]") {
    const Scene scene = instanced_box();
    IntegratorOptions specialised;
    specialised.launch_plan = LaunchPlan::Stages; // one plan for both (test_features.cpp says why)
    IntegratorOptions general = specialised;
    general.general_kernels = true;
    const test::Rendered a = test::render(scene, 2, 7, 0, specialised);
    const test::Rendered b = test::render(scene, 2, 7, 0, general);
    const Image mean_a = a.film.mean(), mean_b = b.film.mean();
    REQUIRE(mean_a.rgb.size() == mean_b.rgb.size());
    CHECK(std::memcmp(mean_a.rgb.data(), mean_b.rgb.data(), mean_a.rgb.size() * sizeof(float)) ==
          0);
    CHECK(a.stats.bounce_rays == b.stats.bounce_rays);
    CHECK(a.stats.shadow_rays == b.stats.shadow_rays);
}

TEST_CASE("instances: instanced mirrors beside a planar mirror render what their flattened copies "
          "do, where next-event estimation samples the copies through the mirrors",
          "[render][instances][statistical]") {
    // A lit box with a plain mirror on a wall (the host's planar mirrors:
    // next-event estimation through it) and mirror tiles placed by three
    // instances, one mirrored. In the instanced scene the tiles are delta
    // bounces of weight 1 (kernels/primitive.h: never a planar mirror of the
    // host's tables); flattened, they join the planar mirrors and light is
    // also sampled through them. Different estimators of the same image.
    Scene scene;
    scene.camera = test::make_camera({0.5, 0.05, 0.5}, {0.5, 1, 0.45}, {0, 0, 1}, 70.0, 32, 32);
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.7));
    const auto mirror = test::add_material(scene, MaterialKind::Mirror, glm::dvec3(0.9));
    const auto light =
        test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(8.0));
    test::add_box_inward(scene, glm::dvec3(0.0), glm::dvec3(1.0), white);
    test::add_quad(scene, {0.4, 0.4, 0.999}, {0.4, 0.6, 0.999}, {0.6, 0.6, 0.999},
                   {0.6, 0.4, 0.999}, light);
    test::add_quad(scene, {0.001, 0.5, 0.2}, {0.001, 0.9, 0.2}, {0.001, 0.9, 0.7},
                   {0.001, 0.5, 0.7}, mirror); // on the x = 0 wall, facing +x
    ShapeGroup tile{"tile", {}};
    tile.triangles.push_back(
        {{glm::dvec3(-1, -1, 0), glm::dvec3(1, -1, 0), glm::dvec3(1, 1, 0)}, mirror});
    tile.triangles.push_back(
        {{glm::dvec3(-1, -1, 0), glm::dvec3(1, 1, 0), glm::dvec3(-1, 1, 0)}, mirror});
    scene.shape_groups = {tile};
    const Transform placements[3][3] = {{Transform::scale(0.12), Transform::rotate(-60, {1, 0, 0}),
                                         Transform::translate({0.3, 0.6, 0.2})},
                                        {Transform::scale(glm::dvec3(-0.15, 0.1, 0.1)),
                                         Transform::rotate(-45, {1, 0.3, 0}),
                                         Transform::translate({0.7, 0.7, 0.25})},
                                        {Transform::scale(0.1), Transform::rotate(80, {0, 1, 0}),
                                         Transform::translate({0.9, 0.5, 0.4})}};
    for (const auto& steps : placements)
        scene.instances.push_back({0, Transform::compose(steps).matrix()});
    const Scene flat = test::flattened_copy(scene);
    REQUIRE(analyse_features(scene).planar_mirrors);
    REQUIRE(analyse_features(flat).planar_mirrors);
    REQUIRE(flatten_scene(flat, true).mirror_triangles.size() >
            flatten_scene(scene, true).mirror_triangles.size());

    const test::Rendered a = test::render(scene, 128, 3);
    const test::Rendered b = test::render(flat, 128, 4); // independent: other seed
    const Image mean_a = a.film.mean(), mean_b = b.film.mean();
    const Image var_a = a.film.variance_of_mean(), var_b = b.film.variance_of_mean();
    double worst = 0.0;
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx)
            for (int c = 0; c < 3; ++c) {
                double sa = 0, sb = 0, va = 0, vb = 0;
                for (int y = by * 8; y < by * 8 + 8; ++y)
                    for (int x = bx * 8; x < bx * 8 + 8; ++x) {
                        const std::size_t i = (std::size_t(y) * 32 + x) * 3 + c;
                        sa += mean_a.rgb[i];
                        sb += mean_b.rgb[i];
                        va += var_a.rgb[i];
                        vb += var_b.rgb[i];
                    }
                const double apart = std::fabs(sa - sb) / std::sqrt(va + vb);
                INFO("block " << bx << "," << by << " channel " << c);
                CHECK(apart < 5.0);
                worst = std::max(worst, apart);
            }
    WARN("instanced mirrors against flattened ones: the worst 8x8 block is " << worst
                                                                             << " sigma apart");
}
