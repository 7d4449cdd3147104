// Smooth vertex normals for meshes whose file has none (or whose normals the
// user asked to replace): each vertex gets the average of the geometric normals
// of the triangles around it, weighted by triangle area. Area weighting is what
// summing the unnormalised cross products gives for free; it lets a sliver next
// to a large face count for little, as it should.
//
// Vertices are the mesh's own: two vertices at the same position (a seam in the
// file) are not welded, so a seam stays visible, as in the file.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace wp {

// One unit normal per position. A vertex that no triangle uses gets (0, 0, 1);
// one whose weighted sum cancels (two faces back to back) gets the normal of its
// largest triangle.
std::vector<glm::dvec3>
smooth_vertex_normals(const std::vector<glm::dvec3>& positions,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles);

} // namespace wp
