// The OBJ reader on small hand-written files (tests/data/meshes/): polygons,
// relative indices, usemtl names, file normals and the vertex split they need.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "scene/mesh.hpp"
#include "support/mesh_test_files.hpp"

using mesh_test::data_dir;

TEST_CASE("obj: the unit cube's quads become 12 outward triangles", "[mesh][obj]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "cube.obj");
    CHECK(m.positions.size() == 8);
    CHECK(m.faces_read == 6);
    REQUIRE(m.triangles.size() == 12);
    CHECK(m.dropped_degenerate == 0);
    CHECK(m.warnings.empty());
    CHECK_FALSE(m.has_normals());
    CHECK(mesh_test::surface_area(m) == Approx(6.0));
    // Outward winding throughout: the divergence theorem gives +1, not less.
    CHECK(mesh_test::signed_volume(m) == Approx(1.0));
    // The last face was written with negative indices; it is the x = 1 side.
    CHECK(mesh_test::face_normal(m, 11).x == Approx(1.0));
}

TEST_CASE("obj: usemtl names are kept per triangle, in file order", "[mesh][obj]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "cube.obj");
    REQUIRE(m.material_names == std::vector<std::string>{"", "red", "blue"});
    const std::vector<std::uint32_t> expected{0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 1, 1};
    CHECK(m.triangle_materials == expected);
}

TEST_CASE("obj: resolve_materials maps names to scene materials or the object's", "[mesh][obj]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "cube.obj");
    std::vector<wp::Material> materials(3);
    materials[0].name = "white";
    materials[1].name = "red";
    materials[2].name = "green";
    std::vector<std::string> warnings;
    const auto ids = wp::resolve_materials(m, materials, 0, warnings);
    const std::vector<std::uint32_t> expected{0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 1, 1};
    CHECK(ids == expected);
    // "blue" is not a scene material: its faces fall back, with one warning.
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Catch::Contains("cube.obj: usemtl 'blue' is not a scene material"));
}

TEST_CASE("obj: negative indices are relative to the vertices defined so far", "[mesh][obj]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "relative.obj");
    REQUIRE(m.triangles.size() == 2);
    CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    CHECK(m.triangles[1] == std::array<std::uint32_t, 3>{0, 1, 3});
}

TEST_CASE("obj: file normals split vertices at a crease and are normalised", "[mesh][obj]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "crease.obj");
    REQUIRE(m.has_normals());
    // Six distinct (position, normal) pairs from four positions.
    REQUIRE(m.positions.size() == 6);
    REQUIRE(m.normals.size() == 6);
    REQUIRE(m.triangles.size() == 2);
    for (const auto& t : m.triangles) {
        // Each triangle's corners carry its own normal.
        CHECK(m.normals[t[0]] == m.normals[t[1]]);
        CHECK(m.normals[t[1]] == m.normals[t[2]]);
    }
    const glm::dvec3 n0 = m.normals[m.triangles[0][0]];
    const glm::dvec3 n1 = m.normals[m.triangles[1][0]];
    CHECK(n0.z == Approx(1.0));
    CHECK(n1.y == Approx(0.6));
    CHECK(n1.z == Approx(0.8));
    CHECK(glm::length(n1) == Approx(1.0));
    // The shared corner (0, 0, 0) appears twice, once per normal.
    CHECK(m.positions[m.triangles[0][0]] == m.positions[m.triangles[1][0]]);
    CHECK(m.triangles[0][0] != m.triangles[1][0]);
}

TEST_CASE("obj: without file normals the positions are not split", "[mesh][obj]") {
    wp::MeshLoadOptions none;
    none.normals = wp::NormalSource::None;
    const wp::TriangleMesh a = wp::load_mesh(data_dir() / "crease.obj", none);
    CHECK(a.positions.size() == 4);
    CHECK_FALSE(a.has_normals());

    wp::MeshLoadOptions smooth;
    smooth.normals = wp::NormalSource::Smooth;
    const wp::TriangleMesh b = wp::load_mesh(data_dir() / "crease.obj", smooth);
    REQUIRE(b.positions.size() == 4);
    REQUIRE(b.normals.size() == 4);
    // Computed from the flat geometry, so the file's tilted normal is gone.
    for (const glm::dvec3& n : b.normals)
        CHECK(n.z == Approx(1.0));
}

TEST_CASE("obj: some corners without a normal drop the file's normals, with a warning",
          "[mesh][obj]") {
    const auto path = mesh_test::write_file("mixed_normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                 "vn 0 0 1\nf 1//1 2//1 3\n");
    const wp::TriangleMesh m = wp::load_mesh(path);
    CHECK_FALSE(m.has_normals());
    REQUIRE(m.warnings.size() == 1);
    CHECK_THAT(m.warnings[0], Catch::Contains("some face corners have no normal"));
}

TEST_CASE("obj: a concave polygon is ear-clipped, not fanned", "[mesh][obj]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "l_shape.obj");
    REQUIRE(m.triangles.size() == 4);
    // A fan from the first corner would overlap outside the L: its unsigned area
    // would exceed 3 and one triangle would face -z.
    CHECK(mesh_test::surface_area(m) == Approx(3.0));
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
        CHECK(mesh_test::face_normal(m, i).z == Approx(1.0));
}

TEST_CASE("obj: faces with more than 255 corners survive tinyobjloader's byte counts",
          "[mesh][obj]") {
    // tinyobjloader stores a face's corner count in an unsigned char; the reader
    // walks its indices with its own counts. A convex 300-gon: 298 triangles.
    std::string obj;
    const int n = 300;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * i / n;
        obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    obj += "f";
    for (int i = 1; i <= n; ++i) {
        obj += ' '; // (not " " + to_string: GCC 12 gives a false -Wrestrict there)
        obj += std::to_string(i);
    }
    obj += "\nf 1 2 3\n";
    const wp::TriangleMesh m = wp::load_mesh(mesh_test::write_file("big_face.obj", obj));
    CHECK(m.faces_read == 2);
    CHECK(m.triangles.size() == 299);
    CHECK(m.triangles.back() == std::array<std::uint32_t, 3>{0, 1, 2});
}

TEST_CASE("obj: degenerate triangles are dropped and counted", "[mesh][obj]") {
    const auto path = mesh_test::write_file(
        "degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
    const wp::TriangleMesh m = wp::load_mesh(path);
    CHECK(m.triangles.size() == 1);
    CHECK(m.dropped_degenerate == 2);
    REQUIRE(m.warnings.size() == 1);
    CHECK_THAT(m.warnings[0], Catch::Contains("dropped 2 degenerate"));
}

TEST_CASE("obj: the extension is matched without regard to case", "[mesh][obj]") {
    const auto path = mesh_test::write_file("upper.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK(wp::load_mesh(path).triangles.size() == 1);
}

TEST_CASE("obj: a UTF-8 byte-order mark before the first line is skipped", "[mesh][obj]") {
    // Without the skip the first line's keyword is "\xEF\xBB\xBFv": the line
    // is dropped and the face's index 3 is out of range.
    const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const wp::TriangleMesh m =
        wp::load_mesh(mesh_test::write_file("bom.obj", "\xEF\xBB\xBF" + body));
    REQUIRE(m.positions.size() == 3);
    REQUIRE(m.triangles.size() == 1);
    CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    CHECK(m.positions[0] == glm::dvec3(0, 0, 0));
    CHECK(m.positions[1] == glm::dvec3(1, 0, 0));
    // A mark before a usemtl, in a file of CRLF lines.
    const wp::TriangleMesh named = wp::load_mesh(mesh_test::write_file(
        "bom_usemtl.obj",
        "\xEF\xBB\xBFusemtl red\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"));
    CHECK(named.material_names == std::vector<std::string>{"", "red"});
    CHECK(named.triangle_materials == std::vector<std::uint32_t>{1});
    // Only at the file's start: elsewhere the bytes are an unknown statement.
    const wp::TriangleMesh later =
        wp::load_mesh(mesh_test::write_file("bom_later.obj", body + "\xEF\xBB\xBFo x\n"));
    CHECK(later.triangles.size() == 1);
}

TEST_CASE("obj: a megabyte-long name or token is quoted in 80 bytes", "[mesh][obj]") {
    const std::string huge(1 << 20, 'n');
    const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    // The usemtl name in the warning of a name that is no scene material.
    const wp::TriangleMesh m =
        wp::load_mesh(mesh_test::write_file("long_usemtl.obj", "usemtl " + huge + "\n" + body));
    std::vector<wp::Material> materials(1);
    materials[0].name = "white";
    std::vector<std::string> warnings;
    wp::resolve_materials(m, materials, 0, warnings);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0].size() < 300);
    CHECK_THAT(warnings[0], Catch::Contains("usemtl '" + std::string(80, 'n') + "...' is not"));
    // A token the reader cannot read, in its error.
    const auto path = mesh_test::write_file("long_token.obj", "v 0 " + huge + " 0\n" + body);
    const std::string error = mesh_test::error_of(path);
    CHECK(error ==
          path.string() + ":1: cannot read vertex coordinate '" + std::string(80, 'n') + "...'");
}
