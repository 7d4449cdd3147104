#include "scene/polygon_triangulation.hpp"

#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace wp {

namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) {
    return a.x * b.y - a.y * b.x;
}

} // namespace

void triangulate_polygon(std::span<const std::uint32_t> corners,
                         const std::vector<glm::dvec3>& positions,
                         std::vector<std::array<std::uint32_t, 3>>& out) {
    const std::size_t n = corners.size();
    if (n < 3)
        return;
    if (n == 3) {
        out.push_back({corners[0], corners[1], corners[2]});
        return;
    }
    // `ring` holds positions in `corners` still to be covered.
    auto fan = [&](const std::vector<std::size_t>& ring) {
        for (std::size_t j = 1; j + 1 < ring.size(); ++j)
            out.push_back({corners[ring[0]], corners[ring[j]], corners[ring[j + 1]]});
    };
    std::vector<std::size_t> ring(n);
    std::iota(ring.begin(), ring.end(), std::size_t{0});

    // The Newell normal: twice the vector area, robust for non-planar input.
    const glm::dvec3 origin = positions[corners[0]];
    glm::dvec3 normal(0.0);
    for (std::size_t i = 0; i < n; ++i)
        normal +=
            glm::cross(positions[corners[i]] - origin, positions[corners[(i + 1) % n]] - origin);
    const glm::dvec3 a = glm::abs(normal);
    const int k = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    if (normal[k] == 0.0) {
        fan(ring); // all corners on a line: every triangle is degenerate anyway
        return;
    }
    // Drop the normal's largest axis; with the other two in cyclic order the
    // projected polygon turns counter-clockwise exactly when normal[k] > 0.
    const int u = (k + 1) % 3;
    const int v = (k + 2) % 3;
    const double orientation = normal[k] > 0.0 ? 1.0 : -1.0;
    std::vector<glm::dvec2> p(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 q = positions[corners[i]] - origin;
        p[i] = {q[u], q[v]};
    }
    // > 0 for a turn the polygon's way at b, 0 for collinear.
    auto turn = [&](std::size_t a0, std::size_t b0, std::size_t c0) {
        return orientation * cross2(p[b0] - p[a0], p[c0] - p[b0]);
    };

    bool convex = true;
    for (std::size_t i = 0; i < n && convex; ++i)
        convex = turn((i + n - 1) % n, i, (i + 1) % n) >= 0.0;
    if (convex || n > max_ear_clipping_corners) {
        fan(ring);
        return;
    }

    auto inside = [&](std::size_t q, std::size_t a0, std::size_t b0, std::size_t c0) {
        return turn(a0, b0, q) >= 0.0 && turn(b0, c0, q) >= 0.0 && turn(c0, a0, q) >= 0.0;
    };
    auto is_ear = [&](std::size_t at) {
        const std::size_t m = ring.size();
        const std::size_t a0 = ring[(at + m - 1) % m];
        const std::size_t b0 = ring[at];
        const std::size_t c0 = ring[(at + 1) % m];
        if (turn(a0, b0, c0) <= 0.0)
            return false;
        for (const std::size_t q : ring) {
            // Corners on top of the ear's own (as in polygons with bridged holes)
            // do not block it.
            if (p[q] == p[a0] || p[q] == p[b0] || p[q] == p[c0])
                continue;
            if (inside(q, a0, b0, c0))
                return false;
        }
        return true;
    };

    std::size_t at = 0;
    while (ring.size() > 3) {
        bool clipped = false;
        for (std::size_t tries = 0; tries < ring.size(); ++tries, at = (at + 1) % ring.size()) {
            if (!is_ear(at))
                continue;
            const std::size_t m = ring.size();
            out.push_back(
                {corners[ring[(at + m - 1) % m]], corners[ring[at]], corners[ring[(at + 1) % m]]});
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(at));
            at %= ring.size();
            clipped = true;
            break;
        }
        if (!clipped) {
            fan(ring); // no ear: not a simple polygon
            return;
        }
    }
    out.push_back({corners[ring[0]], corners[ring[1]], corners[ring[2]]});
}

} // namespace wp
