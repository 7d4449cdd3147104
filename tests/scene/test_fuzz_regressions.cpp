// The mesh and scene fuzzers' findings (tests/support/fuzz_regressions.hpp), and
// the in-memory entry point they read through, parse_mesh, checked against
// load_mesh on the same files.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "scene/load.hpp"
#include "scene/mesh.hpp"
#include "support/fuzz_regressions.hpp"
#include "support/mesh_test_files.hpp"

namespace {

// The two ways mesh_fuzzer.cpp reads every input.
std::vector<wp::MeshLoadOptions> fuzzer_options() {
    wp::MeshLoadOptions file_normals;
    file_normals.normals = wp::NormalSource::File;
    wp::MeshLoadOptions smooth_mirrored;
    smooth_mirrored.normals = wp::NormalSource::Smooth;
    smooth_mirrored.transform = wp::Transform::scale(glm::dvec3(-1.0, 2.0, 0.5));
    smooth_mirrored.shape_index = 1; // as the fuzzer: a .serialized file's second mesh
    return {file_normals, smooth_mirrored};
}

// The message parse_mesh gives for the case ("" when it reads the mesh), after
// checking that the warnings of a mesh it reads are clean.
std::string mesh_outcome(const fuzz_regressions::Case& c, const std::string& name,
                         const wp::MeshLoadOptions& options) {
    try {
        const wp::TriangleMesh mesh = wp::parse_mesh(c.bytes, name, options);
        // As the fuzzer does: `usemtl` names matched against scene materials.
        static const std::vector<wp::Material> scene_materials = {{"white"}, {"red"}, {"blue"}};
        std::vector<std::string> warnings = mesh.warnings;
        CHECK(wp::resolve_materials(mesh, scene_materials, 0, warnings).size() ==
              mesh.triangles.size());
        for (const std::string& warning : warnings) {
            INFO(warning);
            CHECK(wp::fuzz::message_problem(warning).empty());
        }
        return "";
    } catch (const wp::MeshError& e) {
        return e.what();
    }
}

void check_mesh_cases(const std::string& target, const std::string& name) {
    const auto cases = fuzz_regressions::cases(target);
    for (const auto& c : cases)
        for (const wp::MeshLoadOptions& options : fuzzer_options())
            fuzz_regressions::check_outcome(c, mesh_outcome(c, name, options));
}

} // namespace

TEST_CASE("fuzz regressions: OBJ inputs give clean errors", "[fuzz][mesh][obj]") {
    check_mesh_cases("obj", "fuzz.obj");
}

TEST_CASE("fuzz regressions: PLY inputs give clean errors", "[fuzz][mesh][ply]") {
    check_mesh_cases("ply", "fuzz.ply");
}

TEST_CASE("parse_mesh reads a file's bytes as load_mesh reads the file", "[fuzz][mesh]") {
    for (const char* file : {"cube.obj", "crease.obj", "l_shape.obj", "relative.obj",
                             "cube_ascii.ply", "strips.ply", "two-meshes.serialized"}) {
        INFO(file);
        const std::filesystem::path path = mesh_test::data_dir() / file;
        const std::string bytes = fuzz_regressions::read_bytes(path);
        for (const wp::MeshLoadOptions& options : fuzzer_options()) {
            const wp::TriangleMesh from_file = wp::load_mesh(path, options);
            const wp::TriangleMesh from_bytes = wp::parse_mesh(bytes, path, options);
            CHECK(from_bytes.source == from_file.source);
            CHECK(from_bytes.positions == from_file.positions);
            CHECK(from_bytes.normals == from_file.normals);
            CHECK(from_bytes.triangles == from_file.triangles);
            CHECK(from_bytes.material_names == from_file.material_names);
            CHECK(from_bytes.triangle_materials == from_file.triangle_materials);
            CHECK(from_bytes.warnings == from_file.warnings);
            CHECK(!from_bytes.triangles.empty());
        }
    }
    // The format comes from the name alone, as for a file.
    CHECK_THROWS_WITH(wp::parse_mesh("v 0 0 0\n", "mesh.stl"),
                      "mesh.stl: unknown mesh format '.stl' (expected .obj, .ply or .serialized)");
    CHECK_THROWS_WITH(wp::parse_mesh("ply\n", "mesh"),
                      "mesh: unknown mesh format: the file name has no extension (expected .obj, "
                      ".ply or .serialized)");
}

TEST_CASE("OBJ statements a triangle mesh does not use are ignored, whatever they hold",
          "[fuzz][mesh][obj]") {
    const std::string plain = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
    const wp::TriangleMesh reference = wp::parse_mesh(plain, "a.obj");
    // Skin weights, lines, points, tags and curves, with numbers that
    // tinyobjloader's own parsers would mishandle; tinyobjloader never sees them.
    const std::string extra = "vw 1 1e309 0.5\nv 0 0 0\nl 1 99999999999\nv 1 0 0\np -1e400\n"
                              "v 0 1 0\nt crease 2/1/0 1 2 1e309\nv 1 1 0\ncurv 0 1 1 2\n"
                              "f 1 2 3\nunknown words\nf 2 4 3\n";
    const wp::TriangleMesh m = wp::parse_mesh(extra, "a.obj");
    CHECK(m.positions == reference.positions);
    CHECK(m.triangles == reference.triangles);
    // A carriage return inside a line does not end it, for tinyobjloader as for
    // the check pass: the face after it is part of the vertex line.
    CHECK_THROWS_WITH(wp::parse_mesh("v 0 0 0\nv 1 0 0\nv 0 1 0 \rf 1 2 3\n", "b.obj"),
                      "b.obj: mesh has no faces");
    const wp::TriangleMesh crlf =
        wp::parse_mesh("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n", "c.obj");
    CHECK(crlf.triangles.size() == 1);
}
