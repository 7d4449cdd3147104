// Load times of 10^6-triangle meshes, for docs/meshes.md. Hidden from ctest
// (tag [.]); run with
//   build/wavepath_scene_tests "[.bench]" -s
// It writes a torus of 1000 x 500 quads (10^6 triangles, 500,000 vertices) as
// binary little-endian PLY (float x y z, uchar/int triangle lists) and as OBJ
// (%.6f coordinates, triangles) into the temporary folder, then times load_mesh.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "scene/mesh.hpp"
#include "support/mesh_test_files.hpp"

namespace {

constexpr int ring = 1000; // around the big circle
constexpr int tube = 500;  // around the tube

glm::dvec3 torus_point(int i, int j) {
    const double pi = 3.14159265358979323846;
    const double u = 2 * pi * i / ring;
    const double v = 2 * pi * j / tube;
    return {(1.0 + 0.3 * std::cos(v)) * std::cos(u), (1.0 + 0.3 * std::cos(v)) * std::sin(u),
            0.3 * std::sin(v)};
}

std::uint32_t vertex(int i, int j) {
    return static_cast<std::uint32_t>((i % ring) * tube + (j % tube));
}

template <class F> double seconds(F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

TEST_CASE("bench: load 10^6 triangles from binary PLY and OBJ", "[.bench]") {
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(ring * tube) +
        "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
        std::to_string(2 * ring * tube) + "\nproperty list uchar int vertex_indices\nend_header\n";
    std::string obj;
    mesh_test::Bytes body(false);
    char line[128];
    for (int i = 0; i < ring; ++i)
        for (int j = 0; j < tube; ++j) {
            const glm::dvec3 p = torus_point(i, j);
            body.put(static_cast<float>(p.x)).put(static_cast<float>(p.y));
            body.put(static_cast<float>(p.z));
            std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", p.x, p.y, p.z);
            obj += line;
        }
    for (int i = 0; i < ring; ++i)
        for (int j = 0; j < tube; ++j) {
            const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                                d = vertex(i, j + 1);
            for (const auto& t : {std::array<std::uint32_t, 3>{a, b, c}, {a, c, d}}) {
                body.put(std::uint8_t{3});
                for (const std::uint32_t k : t)
                    body.put(static_cast<std::int32_t>(k));
                std::snprintf(line, sizeof line, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
                obj += line;
            }
        }
    ply += body.str();
    const auto ply_path = mesh_test::write_file("torus-1M.ply", ply);
    const auto obj_path = mesh_test::write_file("torus-1M.obj", obj);

    for (int run = 0; run < 3; ++run) {
        std::size_t ply_triangles = 0, obj_triangles = 0;
        const double tp =
            seconds([&] { ply_triangles = wp::load_mesh(ply_path).triangles.size(); });
        const double to =
            seconds([&] { obj_triangles = wp::load_mesh(obj_path).triangles.size(); });
        CHECK(ply_triangles == 1000000);
        CHECK(obj_triangles == 1000000);
        WARN("run " << run << ": binary PLY " << static_cast<double>(ply.size()) / 1e6 << " MB in "
                    << tp << " s, OBJ " << static_cast<double>(obj.size()) / 1e6 << " MB in " << to
                    << " s");
    }
    std::filesystem::remove(ply_path);
    std::filesystem::remove(obj_path);
}
