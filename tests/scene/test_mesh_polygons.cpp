// Polygon triangulation and smooth normals against independent references:
// the shoelace area of random simple polygons, and the exact vertex normals of
// an octahedron.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/mesh.hpp"
#include "scene/mesh_normals.hpp"
#include "scene/polygon_triangulation.hpp"
#include "support/mesh_test_files.hpp"

namespace {

constexpr double pi = 3.14159265358979323846;

// Signed area (shoelace) of a polygon in the plane z = 0.
double shoelace(const std::vector<glm::dvec3>& p) {
    double a = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec3& q = p[i];
        const glm::dvec3& r = p[(i + 1) % p.size()];
        a += q.x * r.y - r.x * q.y;
    }
    return 0.5 * a;
}

} // namespace

TEST_CASE("polygons: random star-shaped polygons are covered exactly", "[mesh][polygons]") {
    // Radius varying with angle gives simple, mostly non-convex polygons; each is
    // then tilted out of the z = 0 plane so the projection code is exercised too.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> radius(0.2, 1.0);
    std::uniform_int_distribution<int> corners(4, 40);
    const glm::dvec3 tilt_axis = glm::normalize(glm::dvec3(1, 2, 0.5));
    int non_convex = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const int n = corners(rng);
        std::vector<glm::dvec3> flat(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            const double a = 2 * pi * i / n;
            const double r = radius(rng);
            flat[static_cast<std::size_t>(i)] = {r * std::cos(a), r * std::sin(a), 0.0};
        }
        const bool clockwise = trial % 2 == 1;
        if (clockwise)
            std::reverse(flat.begin(), flat.end());
        const wp::Transform tilt = wp::Transform::rotate(20.0 + trial, tilt_axis);
        std::vector<glm::dvec3> positions;
        for (const glm::dvec3& p : flat)
            positions.push_back(tilt.apply_to_point(p));
        const glm::dvec3 plane_normal = tilt.apply_to_normal({0, 0, clockwise ? -1 : 1});

        std::vector<std::uint32_t> polygon(static_cast<std::size_t>(n));
        std::iota(polygon.begin(), polygon.end(), 0u);
        std::vector<std::array<std::uint32_t, 3>> triangles;
        wp::triangulate_polygon(polygon, positions, triangles);

        INFO("trial " << trial << ", " << n << " corners");
        REQUIRE(triangles.size() == static_cast<std::size_t>(n - 2));
        double area = 0.0;
        bool fan_would_fail = false;
        for (const auto& t : triangles) {
            const glm::dvec3 c =
                glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
            // Every triangle faces the polygon's way: none folds over.
            CHECK(glm::dot(c, plane_normal) >= -1e-12);
            area += 0.5 * glm::length(c);
        }
        for (int j = 1; j + 1 < n; ++j) {
            const glm::dvec3 c =
                glm::cross(positions[static_cast<std::size_t>(j)] - positions[0],
                           positions[static_cast<std::size_t>(j + 1)] - positions[0]);
            fan_would_fail |= glm::dot(c, plane_normal) < 0.0;
        }
        non_convex += fan_would_fail;
        CHECK(area == Approx(std::abs(shoelace(flat))).epsilon(1e-9));
    }
    // Most of these polygons defeat a plain fan, so the check above means something.
    CHECK(non_convex > 100);
}

TEST_CASE("polygons: convex polygons become a fan around the first corner", "[mesh][polygons]") {
    const std::vector<glm::dvec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> polygon{0, 1, 2, 3};
    std::vector<std::array<std::uint32_t, 3>> t;
    wp::triangulate_polygon(polygon, square, t);
    REQUIRE(t.size() == 2);
    CHECK(t[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    CHECK(t[1] == std::array<std::uint32_t, 3>{0, 2, 3});
}

TEST_CASE("polygons: a polygon on a line gives only degenerate triangles", "[mesh][polygons]") {
    const std::vector<glm::dvec3> line{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    const std::vector<std::uint32_t> polygon{0, 1, 2, 3};
    std::vector<std::array<std::uint32_t, 3>> t;
    wp::triangulate_polygon(polygon, line, t);
    CHECK(t.size() == 2); // the loader then drops them as zero-area
}

TEST_CASE("smooth normals: an octahedron's vertices point away from its centre",
          "[mesh][normals]") {
    const auto path =
        mesh_test::write_file("octahedron.obj", "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                                "v 0 0 -1\n"
                                                "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\n"
                                                "f 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
    wp::MeshLoadOptions o;
    o.normals = wp::NormalSource::Smooth;
    const wp::TriangleMesh m = wp::load_mesh(path, o);
    REQUIRE(mesh_test::signed_volume(m) == Approx(4.0 / 3.0)); // outward winding
    REQUIRE(m.normals.size() == 6);
    for (std::size_t i = 0; i < 6; ++i)
        CHECK(glm::dot(m.normals[i], glm::normalize(m.positions[i])) == Approx(1.0));
}

TEST_CASE("smooth normals: area weighting, cancellation and unused vertices", "[mesh][normals]") {
    // Vertex 0 is shared by a large triangle facing +z and a small one facing +x.
    const std::vector<glm::dvec3> p{{0, 0, 0}, {4, 0, 0}, {0, 4, 0},
                                    {0, 1, 0}, {0, 0, 1}, {9, 9, 9}};
    const std::vector<std::array<std::uint32_t, 3>> t{{0, 1, 2}, {0, 3, 4}};
    const auto n = wp::smooth_vertex_normals(p, t);
    // Areas 8 and 0.5: the sum is 8 (0,0,1) + 0.5 (1,0,0).
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0.5, 0, 8));
    CHECK(glm::length(n[0] - expected) < 1e-12);
    CHECK(n[1] == glm::dvec3(0, 0, 1));
    CHECK(n[3] == glm::dvec3(1, 0, 0));
    CHECK(n[5] == glm::dvec3(0, 0, 1)); // unused

    // Back to back: the sum cancels, the largest face decides.
    const std::vector<std::array<std::uint32_t, 3>> sheet{{0, 1, 2}, {0, 2, 1}};
    const auto s = wp::smooth_vertex_normals(p, sheet);
    CHECK(glm::length(s[0]) == Approx(1.0));
    CHECK(std::abs(s[0].z) == Approx(1.0));
}
