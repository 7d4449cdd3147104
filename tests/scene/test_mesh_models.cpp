// The four public test models in ../shared/models (see its README.md for the
// face counts checked here). Skipped, with a warning, where that folder is absent.
#include <catch2/catch.hpp>

#include <filesystem>

#include <glm/geometric.hpp>

#include "scene/mesh.hpp"
#include "support/mesh_test_files.hpp"

namespace {

std::filesystem::path models_dir() {
    return std::filesystem::path(WAVEPATH_SOURCE_DIR "/../shared/models");
}

bool have_models() {
    if (std::filesystem::is_directory(models_dir()))
        return true;
    WARN("skipped: no shared models at " << models_dir().string());
    return false;
}

} // namespace

TEST_CASE("models: triangle counts of the four shared models", "[mesh][models]") {
    if (!have_models())
        return;
    struct Model {
        const char* file;
        std::size_t faces;
        std::size_t triangles;
    };
    for (const Model& m :
         {Model{"stanford-bunny.obj", 69451, 69451}, Model{"teapot.obj", 6320, 6320},
          Model{"spot.obj", 5856, 5856}, Model{"suzanne.obj", 500, 468 * 2 + 32}}) {
        INFO(m.file);
        const wp::TriangleMesh mesh = wp::load_mesh(models_dir() / m.file);
        CHECK(mesh.faces_read == m.faces);
        CHECK(mesh.triangles.size() + mesh.dropped_degenerate == m.triangles);
        CHECK(mesh.dropped_degenerate == 0);
        CHECK(mesh.triangle_materials.size() == mesh.triangles.size());
    }
}

TEST_CASE("models: suzanne's file normals are loaded and agree with its faces", "[mesh][models]") {
    if (!have_models())
        return;
    const wp::TriangleMesh m = wp::load_mesh(models_dir() / "suzanne.obj");
    REQUIRE(m.has_normals());
    REQUIRE(m.normals.size() == m.positions.size());
    // Smooth shading normals lean away from the face normal, but on a closed,
    // consistently wound model they stay on its front side almost everywhere.
    std::size_t agree = 0;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const glm::dvec3 f = mesh_test::face_normal(m, i);
        const auto& t = m.triangles[i];
        const glm::dvec3 avg = m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]];
        agree += glm::dot(f, avg) > 0.0;
        for (const std::uint32_t v : t)
            CHECK(glm::length(m.normals[v]) == Approx(1.0));
    }
    CHECK(agree >= m.triangles.size() * 99 / 100);
}

TEST_CASE("models: the bunny with smooth normals and a transform", "[mesh][models]") {
    if (!have_models())
        return;
    wp::MeshLoadOptions o;
    o.normals = wp::NormalSource::Smooth;
    const std::vector<wp::Transform> steps{wp::Transform::scale(10.0),
                                           wp::Transform::rotate(90, {1, 0, 0}),
                                           wp::Transform::translate({0, 0, 1})};
    o.transform = wp::Transform::compose(steps);
    const wp::TriangleMesh plain = wp::load_mesh(models_dir() / "stanford-bunny.obj");
    const wp::TriangleMesh m = wp::load_mesh(models_dir() / "stanford-bunny.obj", o);
    REQUIRE(m.normals.size() == m.positions.size());
    CHECK(m.triangles == plain.triangles);
    // Uniform scale 10: areas grow by 100.
    CHECK(mesh_test::surface_area(m) ==
          Approx(100.0 * mesh_test::surface_area(plain)).epsilon(1e-9));
}
