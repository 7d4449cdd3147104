// The PLY reader: ASCII files from tests/data/meshes/ and binary files of both
// byte orders written here byte by byte (mesh_test::Bytes), for every scalar type.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "scene/mesh.hpp"
#include "support/mesh_test_files.hpp"

using mesh_test::Bytes;
using mesh_test::data_dir;

namespace {

// The unit cube of cube.obj, 0-based.
const double cube_positions[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const int cube_quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};

// Writes one value of the PLY type `type`.
void put(Bytes& b, const std::string& type, double v) {
    if (type == "char" || type == "int8")
        b.put(static_cast<std::int8_t>(v));
    else if (type == "uchar" || type == "uint8")
        b.put(static_cast<std::uint8_t>(v));
    else if (type == "short" || type == "int16")
        b.put(static_cast<std::int16_t>(v));
    else if (type == "ushort" || type == "uint16")
        b.put(static_cast<std::uint16_t>(v));
    else if (type == "int" || type == "int32")
        b.put(static_cast<std::int32_t>(v));
    else if (type == "uint" || type == "uint32")
        b.put(static_cast<std::uint32_t>(v));
    else if (type == "float" || type == "float32")
        b.put(static_cast<float>(v));
    else
        b.put(v);
}

struct CubeLayout {
    bool big_endian = false;
    std::string coordinate = "float";
    std::string count = "uchar";
    std::string index = "int";
    bool normals = false;
};

// The cube as binary PLY: x, a skipped confidence value, y, z (and normals
// pointing away from the centre), then quads.
std::string binary_cube(const CubeLayout& l) {
    std::string header = std::string("ply\nformat ") +
                         (l.big_endian ? "binary_big_endian" : "binary_little_endian") +
                         " 1.0\nelement vertex 8\nproperty " + l.coordinate +
                         " x\nproperty float confidence\nproperty " + l.coordinate +
                         " y\nproperty " + l.coordinate + " z\n";
    if (l.normals)
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    header += "element face 6\nproperty list " + l.count + " " + l.index +
              " vertex_indices\nend_header\n";
    Bytes b(l.big_endian);
    for (const auto& p : cube_positions) {
        put(b, l.coordinate, p[0]);
        b.put(0.5f);
        put(b, l.coordinate, p[1]);
        put(b, l.coordinate, p[2]);
        if (l.normals)
            for (int k = 0; k < 3; ++k)
                b.put(static_cast<float>(p[k] - 0.5));
    }
    for (const auto& q : cube_quads) {
        put(b, l.count, 4);
        for (int k = 0; k < 4; ++k)
            put(b, l.index, q[k]);
    }
    return header + b.str();
}

void check_is_the_cube(const wp::TriangleMesh& m) {
    REQUIRE(m.positions.size() == 8);
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k)
            CHECK(m.positions[i][k] == cube_positions[i][k]);
    CHECK(m.faces_read == 6);
    REQUIRE(m.triangles.size() == 12);
    CHECK(mesh_test::surface_area(m) == Approx(6.0));
    CHECK(mesh_test::signed_volume(m) == Approx(1.0));
    CHECK(m.material_names == std::vector<std::string>{""});
    CHECK(m.triangle_materials == std::vector<std::uint32_t>(12, 0));
}

} // namespace

TEST_CASE("ply: ASCII with reordered and extra properties and a skipped element", "[mesh][ply]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "cube_ascii.ply");
    check_is_the_cube(m);
    CHECK_FALSE(m.has_normals());
}

TEST_CASE("ply: ASCII gives the same mesh as the OBJ of the same cube", "[mesh][ply]") {
    const wp::TriangleMesh ply = wp::load_mesh(data_dir() / "cube_ascii.ply");
    const wp::TriangleMesh obj = wp::load_mesh(data_dir() / "cube.obj");
    CHECK(ply.positions == obj.positions);
    CHECK(ply.triangles == obj.triangles);
}

TEST_CASE("ply: binary in both byte orders and every scalar type", "[mesh][ply]") {
    const auto big_endian = GENERATE(false, true);
    const auto coordinate =
        GENERATE(as<std::string>{}, "float", "double", "float32", "float64", "short", "uchar");
    const auto index = GENERATE(as<std::string>{}, "int", "uint", "short", "ushort", "char",
                                "uchar", "int32", "uint8");
    const auto count = GENERATE(as<std::string>{}, "uchar", "int", "ushort");
    CubeLayout l;
    l.big_endian = big_endian;
    l.coordinate = coordinate;
    l.index = index;
    l.count = count;
    const std::string name = std::string("cube_") + (big_endian ? "be_" : "le_") + coordinate +
                             "_" + index + "_" + count + ".ply";
    INFO(name);
    check_is_the_cube(wp::load_mesh(mesh_test::write_file(name, binary_cube(l))));
}

TEST_CASE("ply: vertex normals are read and normalised", "[mesh][ply]") {
    CubeLayout l;
    l.normals = true;
    l.big_endian = true;
    const wp::TriangleMesh m =
        wp::load_mesh(mesh_test::write_file("cube_normals.ply", binary_cube(l)));
    REQUIRE(m.normals.size() == 8);
    for (std::size_t i = 0; i < 8; ++i) {
        const glm::dvec3 outward = glm::normalize(m.positions[i] - glm::dvec3(0.5));
        CHECK(glm::dot(m.normals[i], outward) == Approx(1.0));
    }
}

TEST_CASE("ply: triangle strips with restarts, alternating winding and a degenerate",
          "[mesh][ply]") {
    const wp::TriangleMesh m = wp::load_mesh(data_dir() / "strips.ply");
    CHECK(m.faces_read == 5);
    REQUIRE(m.triangles.size() == 4);
    CHECK(m.dropped_degenerate == 1);
    CHECK(mesh_test::surface_area(m) == Approx(2.0));
    // Alternating winding keeps every strip triangle facing the same way.
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
        CHECK(mesh_test::face_normal(m, i).z == Approx(1.0));
    CHECK(m.triangles[1] == std::array<std::uint32_t, 3>{2, 1, 3});
}

TEST_CASE("ply: vertex_index is accepted as the face list's name", "[mesh][ply]") {
    const auto path = mesh_test::write_file(
        "vertex_index.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                            "property float y\nproperty float z\nelement face 1\n"
                            "property list uchar uint vertex_index\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    CHECK(wp::load_mesh(path).triangles.size() == 1);
}

TEST_CASE("ply: CRLF line ends in header and body", "[mesh][ply]") {
    const auto path = mesh_test::write_file(
        "crlf.ply", "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\n"
                    "property float y\r\nproperty float z\r\nelement face 1\r\n"
                    "property list uchar int vertex_indices\r\nend_header\r\n"
                    "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n");
    CHECK(wp::load_mesh(path).triangles.size() == 1);
}

TEST_CASE("ply: elements may come in any order", "[mesh][ply]") {
    const auto path = mesh_test::write_file(
        "faces_first.ply", "ply\nformat ascii 1.0\nelement face 1\n"
                           "property list uchar int vertex_indices\nelement vertex 3\n"
                           "property float x\nproperty float y\nproperty float z\nend_header\n"
                           "3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n");
    const wp::TriangleMesh m = wp::load_mesh(path);
    REQUIRE(m.triangles.size() == 1);
    CHECK(mesh_test::face_normal(m, 0).z == Approx(1.0));
}
