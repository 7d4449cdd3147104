// Planar mirrors for next-event estimation through them (kernels/mirror_light.h):
// the scene's flat mirror triangles grouped by the plane they lie in, and a
// double-precision reference of the mirror point between two points.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "scene/scene.hpp"

namespace wp {

// Coplanar mirror triangles: `normal` (unit) and `offset` give the plane
// dot(normal, p) == offset; `triangles` index Scene::triangles.
struct PlanarMirror {
    glm::dvec3 normal{0.0};
    double offset = 0.0;
    std::vector<std::uint32_t> triangles;
};

// Every triangle of a mirror material without vertex normals (a perfect
// planar mirror) and of non-zero area, grouped by plane: a triangle joins the
// first group whose plane holds its three vertices within 1e-9 of the scene's
// extent and whose normal is parallel to its own within 1e-9 (either
// orientation: mirrors reflect on both sides).
std::vector<PlanarMirror> find_planar_mirrors(const Scene& scene);

// The point where the path x -> mirror -> y meets the mirror's plane, in
// double precision: the crossing of x -> y' (y reflected in the plane) with
// it. Empty unless x and y lie strictly on the same side of the plane and
// the point lies inside (or on the edge of) one of `triangles`, given as
// vertex triples.
struct MirrorPoint {
    glm::dvec3 point{0.0};
    std::size_t triangle = 0; // which of `triangles`
};
std::optional<MirrorPoint> mirror_point(const glm::dvec3& normal, double offset,
                                        const std::vector<std::array<glm::dvec3, 3>>& triangles,
                                        const glm::dvec3& x, const glm::dvec3& y);

} // namespace wp
