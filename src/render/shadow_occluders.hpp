// Which triangles can block a shadow ray: the scene's bounding faces cannot.
//
// A bounding face is a triangle whose plane has the whole scene (every
// vertex, every sphere) and the camera's eye on one closed side, the eye
// strictly: the walls, floor and ceiling of a closed convex room, a floor that
// everything stands on. Every point a path reaches lies on the scene's
// surfaces, so on that side, and so does each shadow ray's end (a point on a
// light, or on a planar mirror); a segment between two points of a closed
// half-space meets its boundary plane at an inner point only if it lies in
// the plane. So no bounding face can block a shadow ray, and the shadow
// stage tests only the other triangles (kernels/traverse.h,
// wp_shadow_occluded): on the hexroom 5 of 26.
//
// That holds for the segments' true ends. A ray's origin is offset from its
// surface (kernels/ray_offset.h); where the offset carries it through a
// bounding plane (a point within the offset's distance of a face it meets at
// an angle), the full test may see that face and report a shadow the exact
// segment does not have; the culled test does not. Scenes with vertex
// normals are left out: their rays start from the smooth surface the normals
// describe (kernels/primitive.h), which may lie beyond the flat triangles.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace wp {

// The triangles (indices into Scene::triangles, ascending) that are not
// bounding faces of `scene`. All of them for a scene with vertex normals. A
// point within 1e-6 of the scene's extent of a plane counts as on it (float32
// rounding of the stored vertices is about 1e-7 of it), the eye must be
// farther than that.
std::vector<std::uint32_t> shadow_occluders(const Scene& scene);

} // namespace wp
