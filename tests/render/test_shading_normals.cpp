// Shading normals and the shadow terminator fix (kernels/primitive.h).
//
// A coarse mesh of a sphere (a 10 x 5 UV sphere, 80 triangles) whose vertex
// normals are the true sphere's, lit from the side, against the analytic
// sphere it approximates. With shading normals the mesh shades like the
// sphere, but its rays start on flat facets, and along the terminator the
// neighbouring facets block light the smooth sphere would get: the image is
// darker there (the artefact). Starting rays from the smooth surface that
// the vertex normals describe removes most of it (the fix).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "image/png.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

// A sphere of radius 1 at the origin lit by a square light on its +x side,
// seen from -z; nothing else, so only light from the sphere reaches the film.
Scene lit_from_the_side() {
    Scene scene;
    scene.camera = test::make_camera({0, 0, -4}, {0, 0, 0}, {0, 1, 0}, 35.0, 48, 48);
    const auto light =
        test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(10.0));
    // Facing -x (towards the sphere): front = cross(b - a, c - a).
    test::add_quad(scene, {4, -1, -1}, {4, -1, 1}, {4, 1, 1}, {4, 1, -1}, light);
    return scene;
}

Scene analytic() {
    Scene scene = lit_from_the_side();
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.8));
    scene.spheres.push_back({glm::dvec3(0.0), 1.0, white});
    return scene;
}

// The UV sphere with the true normals at its vertices (it is inscribed: every
// vertex on the sphere). Front faces outwards.
Scene coarse_mesh(bool normals) {
    Scene scene = lit_from_the_side();
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.8));
    const int slices = 10, stacks = 5;
    auto point = [&](int i, int j) {
        const double theta = M_PI * j / stacks, phi = 2 * M_PI * i / slices;
        return glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                          std::sin(theta) * std::sin(phi));
    };
    auto add = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
        Triangle t{{a, c, b}, white}; // outward winding
        if (glm::dot(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]), a + b + c) < 0)
            std::swap(t.v[1], t.v[2]);
        t.has_normals = normals;
        t.normals = {t.v[0], t.v[1], t.v[2]}; // unit: the vertices are on the unit sphere
        scene.triangles.push_back(t);
    };
    for (int j = 0; j < stacks; ++j)
        for (int i = 0; i < slices; ++i) {
            const glm::dvec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1),
                             d = point(i, j + 1);
            if (j > 0)
                add(a, b, c);
            if (j < stacks - 1)
                add(a, c, d);
        }
    return scene;
}

// The mean green of a render. With WAVEPATH_TEST_IMAGES=DIR set, renders at
// 192 x 192 and writes the image to DIR (docs/images/terminator-*.png).
test::MeanWithError brightness(Scene scene, bool fix, const char* png) {
    IntegratorOptions options;
    options.shadow_terminator_fix = fix;
    const char* dir = std::getenv("WAVEPATH_TEST_IMAGES");
    if (dir)
        scene.camera.width = scene.camera.height = 192;
    test::Rendered r = test::render(scene, 64, 5, 0, options);
    if (dir)
        write_png(std::filesystem::path(dir) / png, r.film.mean(), {});
    return test::image_mean(r.film, 1);
}

} // namespace

TEST_CASE("shading normals: a coarse mesh shades like the sphere it approximates, once the shadow "
          "terminator is fixed",
          "[render][shading-normals][statistical]") {
    const test::MeanWithError sphere = brightness(analytic(), true, "terminator-sphere.png");
    const test::MeanWithError flat = brightness(coarse_mesh(false), true, "terminator-flat.png");
    const test::MeanWithError artefact =
        brightness(coarse_mesh(true), false, "terminator-artefact.png");
    const test::MeanWithError fixed = brightness(coarse_mesh(true), true, "terminator-fixed.png");
    auto sigma = [](const test::MeanWithError& a, const test::MeanWithError& b) {
        return std::hypot(a.standard_error, b.standard_error);
    };
    WARN("mean green: analytic sphere "
         << sphere.mean << ", flat facets " << flat.mean << ", shading normals " << artefact.mean
         << ", with the terminator fix " << fixed.mean << " (standard errors about "
         << fixed.standard_error << ")");
    // The artefact is real: the fix brightens the mesh by many standard errors.
    CHECK(fixed.mean - artefact.mean > 5.0 * sigma(fixed, artefact));
    // And it brings the mesh closer to the sphere it stands for (what is left
    // is mostly the silhouette: the inscribed mesh covers fewer pixels, as the
    // flat-faceted mesh shows).
    CHECK(std::fabs(artefact.mean - sphere.mean) - std::fabs(fixed.mean - sphere.mean) >
          5.0 * sigma(fixed, artefact));
    // The fix only lifts ray origins: a mesh without normals is unaffected by it.
    CHECK(flat.mean > 0.0);
}
