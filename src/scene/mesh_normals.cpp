#include "scene/mesh_normals.hpp"

#include <glm/geometric.hpp>

namespace wp {

std::vector<glm::dvec3>
smooth_vertex_normals(const std::vector<glm::dvec3>& positions,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles) {
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    std::vector<glm::dvec3> largest(positions.size(), glm::dvec3(0.0));
    for (const auto& t : triangles) {
        // |cross| is twice the area, so the sum is area weighted.
        const glm::dvec3 n =
            glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
        const double n2 = glm::dot(n, n);
        for (const std::uint32_t v : t) {
            sum[v] += n;
            if (n2 > glm::dot(largest[v], largest[v]))
                largest[v] = n;
        }
    }
    std::vector<glm::dvec3> normals(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const double s = glm::length(sum[v]);
        const double l = glm::length(largest[v]);
        // The sum "cancels" when it is tiny next to the largest face it contains.
        if (l == 0.0)
            normals[v] = glm::dvec3(0.0, 0.0, 1.0);
        else if (s <= 1e-9 * l)
            normals[v] = largest[v] / l;
        else
            normals[v] = sum[v] / s;
    }
    return normals;
}

} // namespace wp
