#include "render/planar_mirrors.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace wp {

std::vector<PlanarMirror> find_planar_mirrors(const Scene& scene) {
    // Without a mirror material there is nothing to find: no pass over a
    // big mesh's triangles (two of them per load, 2 % of a 10^6-triangle
    // PLY load's samples).
    if (std::none_of(scene.materials.begin(), scene.materials.end(),
                     [](const Material& m) { return m.kind == MaterialKind::Mirror; }))
        return {};
    double extent = 0.0;
    for (const Triangle& t : scene.triangles)
        for (const glm::dvec3& v : t.v)
            extent = std::max({extent, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    const double distance_tolerance = 1e-9 * std::max(extent, 1e-300);
    std::vector<PlanarMirror> groups;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        if (scene.materials[t.material].kind != MaterialKind::Mirror || t.has_normals)
            continue;
        const glm::dvec3 c = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
        const double length = glm::length(c);
        if (!(length > 0.0))
            continue;
        const glm::dvec3 n = c / length;
        auto in_plane = [&](const PlanarMirror& g) {
            if (glm::length(glm::cross(g.normal, n)) > 1e-9)
                return false;
            return std::all_of(t.v.begin(), t.v.end(), [&](const glm::dvec3& v) {
                return std::abs(glm::dot(g.normal, v) - g.offset) <= distance_tolerance;
            });
        };
        auto group = std::find_if(groups.begin(), groups.end(), in_plane);
        if (group == groups.end()) {
            groups.push_back({n, glm::dot(n, t.v[0]), {}});
            group = groups.end() - 1;
        }
        group->triangles.push_back(static_cast<std::uint32_t>(i));
    }
    return groups;
}

std::optional<MirrorPoint> mirror_point(const glm::dvec3& normal, double offset,
                                        const std::vector<std::array<glm::dvec3, 3>>& triangles,
                                        const glm::dvec3& x, const glm::dvec3& y) {
    const double sx = glm::dot(normal, x) - offset;
    const double sy = glm::dot(normal, y) - offset;
    if (!(sx * sy > 0.0))
        return std::nullopt;
    const glm::dvec3 mirrored = y - 2.0 * sy * normal;
    glm::dvec3 p = x + (sx / (sx + sy)) * (mirrored - x);
    p -= (glm::dot(normal, p) - offset) * normal;
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        const auto& v = triangles[k];
        const glm::dvec3 nt = glm::cross(v[1] - v[0], v[2] - v[0]);
        bool inside = true;
        for (int e = 0; e < 3; ++e)
            inside = inside && glm::dot(glm::cross(v[(e + 1) % 3] - v[e], p - v[e]), nt) >= 0.0;
        if (inside)
            return MirrorPoint{p, k};
    }
    return std::nullopt;
}

} // namespace wp
