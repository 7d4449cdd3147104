// Splitting one planar polygon into triangles with the polygon's own winding.
//   - Triangles pass through unchanged.
//   - Convex polygons (every turn the same way in the polygon's plane; collinear
//     corners allowed) become a fan around the first corner.
//   - Non-convex polygons are ear-clipped in their plane (the plane of the Newell
//     normal), which is correct for any simple polygon: no triangle covers area
//     outside it.
//   - When no ear can be found (self-intersecting or badly non-planar polygons),
//     or a non-convex polygon has more than max_ear_clipping_corners corners
//     (ear clipping is quadratic to cubic in the corner count), the rest becomes
//     a fan. Such input has no right answer; the fan covers its corners.
// Zero-area triangles can come out (collinear corners); the caller drops them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace wp {

inline constexpr std::size_t max_ear_clipping_corners = 1024;

// Appends the triangles of the polygon `corners` (indices into positions) to out.
void triangulate_polygon(std::span<const std::uint32_t> corners,
                         const std::vector<glm::dvec3>& positions,
                         std::vector<std::array<std::uint32_t, 3>>& out);

} // namespace wp
