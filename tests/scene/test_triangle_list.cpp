// TriangleList (scene/triangle_list.hpp): triangles held whole and meshes
// held indexed read as one list in order; a triangle changed by set() or
// removed by pop_back() is held whole from then on; copies share meshes
// and a list moved from is empty. Checked against a std::vector<Triangle>
// built from the same triangles.
#include <catch2/catch.hpp>

#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "scene/triangle_list.hpp"

namespace {

using wp::IndexedTriangles;
using wp::Triangle;
using wp::TriangleList;

bool same(const Triangle& a, const Triangle& b) {
    return a.v == b.v && a.material == b.material && a.has_normals == b.has_normals &&
           a.normals == b.normals && a.has_uvs == b.has_uvs && a.uvs == b.uvs;
}

Triangle whole(double z, std::uint32_t material) {
    return {{glm::dvec3(0, 0, z), glm::dvec3(1, 0, z), glm::dvec3(0, 1, z)}, material};
}

// A square of two triangles with normals and texture coordinates, materials 3 and 4.
IndexedTriangles square() {
    IndexedTriangles m;
    m.positions = {{0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
    m.normals = {{0, 0, 1}, {0, 0.6, 0.8}, {0, 0, 1}, {0.6, 0, 0.8}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.corners = {{0, 1, 2}, {0, 2, 3}};
    m.materials = {3, 4};
    return m;
}

// The square's triangles as the loaders stored them whole.
std::vector<Triangle> square_whole() {
    const IndexedTriangles m = square();
    std::vector<Triangle> out;
    for (std::size_t t = 0; t < m.corners.size(); ++t) {
        const auto& [a, b, c] = m.corners[t];
        Triangle w{{m.positions[a], m.positions[b], m.positions[c]}, m.materials[t]};
        w.has_normals = true;
        w.normals = {m.normals[a], m.normals[b], m.normals[c]};
        w.has_uvs = true;
        w.uvs = {m.uvs[a], m.uvs[b], m.uvs[c]};
        out.push_back(w);
    }
    return out;
}

void check_equal(const TriangleList& list, const std::vector<Triangle>& want) {
    REQUIRE(list.size() == want.size());
    CHECK(list.empty() == want.empty());
    std::size_t i = 0;
    for (const Triangle& t : list) {
        INFO("triangle " << i);
        CHECK(same(t, want[i]));
        CHECK(same(list[i], want[i]));
        ++i;
    }
    CHECK(i == want.size());
}

} // namespace

TEST_CASE("triangle list: whole and indexed triangles read as one list, in order") {
    TriangleList list;
    std::vector<Triangle> want;
    check_equal(list, want);
    list.push_back(whole(5, 1));
    want.push_back(whole(5, 1));
    list.append(square());
    for (const Triangle& t : square_whole())
        want.push_back(t);
    list.push_back(whole(6, 2));
    list.push_back(whole(7, 0));
    want.push_back(whole(6, 2));
    want.push_back(whole(7, 0));
    IndexedTriangles plain = square(); // no normals or uvs, one material
    plain.normals.clear();
    plain.uvs.clear();
    plain.materials.clear();
    plain.material = 9;
    list.append(plain);
    want.push_back({{glm::dvec3(0, 0, 1), glm::dvec3(2, 0, 1), glm::dvec3(2, 2, 1)}, 9});
    want.push_back({{glm::dvec3(0, 0, 1), glm::dvec3(2, 2, 1), glm::dvec3(0, 2, 1)}, 9});
    list.append(IndexedTriangles{}); // an empty mesh adds nothing
    check_equal(list, want);
    CHECK(same(list.front(), want.front()));
    CHECK(same(list.back(), want.back()));
    CHECK_THROWS_AS(list[want.size()], std::out_of_range);

    SECTION("set and pop_back") {
        Triangle changed = list[2]; // the square's second triangle
        changed.material = 7;
        changed.v[0].x = -1.0;
        list.set(2, changed);
        want[2] = changed;
        check_equal(list, want);
        list.pop_back(); // from the plain mesh
        want.pop_back();
        check_equal(list, want);
        list.pop_back();
        want.pop_back();
        list.pop_back();
        want.pop_back();
        list.push_back(whole(8, 5));
        want.push_back(whole(8, 5));
        check_equal(list, want);
    }
    SECTION("copies, moves, clear") {
        const TriangleList copy = list;
        check_equal(copy, want);
        TriangleList moved = std::move(list);
        check_equal(moved, want);
        CHECK(list.empty()); // NOLINT(bugprone-use-after-move): moved from is empty
        CHECK(list.heap_bytes() == 0);
        moved.clear();
        CHECK(moved.empty());
        CHECK(moved.heap_bytes() == 0);
        check_equal(copy, want);
    }
    SECTION("built from an initializer list") {
        const TriangleList two{whole(1, 0), whole(2, 1)};
        check_equal(two, {whole(1, 0), whole(2, 1)});
    }
}

TEST_CASE("triangle list: an indexed mesh holds its vertices once, not 208 bytes a triangle") {
    // An n x n grid of quads: (n + 1)^2 vertices, 2 n^2 triangles, no normals.
    const std::uint32_t n = 100;
    IndexedTriangles grid;
    grid.positions.reserve((n + 1) * (n + 1));
    grid.corners.reserve(2 * n * n);
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i)
            grid.positions.emplace_back(i, j, 0.0);
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            grid.corners.push_back({a, b, c});
            grid.corners.push_back({a, c, d});
        }
    TriangleList list;
    list.append(std::move(grid));
    REQUIRE(list.size() == 2 * n * n);
    // 24 bytes a vertex (half as many as triangles) and 12 a triangle: about
    // 24 bytes a triangle, where whole triangles take sizeof(Triangle).
    const double per_triangle = double(list.heap_bytes()) / double(list.size());
    CHECK(per_triangle < 25.0);
    CHECK(sizeof(Triangle) == 208);
    // Read back, the triangle is the grid's.
    const Triangle last = list.back();
    CHECK(last.v[0] == glm::dvec3(n - 1, n - 1, 0));
    CHECK(last.v[2] == glm::dvec3(n - 1, n, 0));
    CHECK_FALSE(last.has_normals);
    CHECK_FALSE(last.has_uvs);
}
