// Scenes with instances for the tests: random shape groups and placements,
// and the same geometry flattened into plain triangles (the reference the
// instanced traversal and renders are held against).
#pragma once

#include <cmath>
#include <random>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "scene/scene.hpp"
#include "scene/transform.hpp"

namespace wp::test {

// A random placement: scaled per axis by 0.4 to 1.6 (mirrored along x when
// `mirror`), turned about a random axis, moved into `lower`..`upper`.
inline glm::dmat4 random_placement(std::mt19937& generator, bool mirror, glm::dvec3 lower,
                                   glm::dvec3 upper) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 scale(0.4 + 1.2 * unit(generator), 0.4 + 1.2 * unit(generator),
                           0.4 + 1.2 * unit(generator));
    const glm::dvec3 axis(unit(generator) - 0.5, unit(generator) - 0.5, unit(generator) + 0.1);
    const glm::dvec3 at =
        lower + (upper - lower) * glm::dvec3(unit(generator), unit(generator), unit(generator));
    const Transform steps[] = {Transform::scale(mirror ? scale * glm::dvec3(-1, 1, 1) : scale),
                               Transform::rotate(360.0 * unit(generator), axis),
                               Transform::translate(at)};
    return Transform::compose(steps).matrix();
}

// A triangle placed by `to_world` as a plain triangle: vertices mapped, vertex
// normals by the inverse transpose, and under a mirroring map the winding
// reversed, so that its front stays where the instance's is (Mitsuba's
// convention, kernels/instance.h).
inline Triangle placed_triangle(const Triangle& t, const glm::dmat4& to_world) {
    const glm::dmat3 normal_map = glm::transpose(glm::inverse(glm::dmat3(to_world)));
    Triangle out = t;
    for (int k = 0; k < 3; ++k) {
        out.v[k] = glm::dvec3(to_world * glm::dvec4(t.v[k], 1.0));
        if (t.has_normals)
            out.normals[k] = glm::normalize(normal_map * t.normals[k]);
    }
    if (glm::determinant(glm::dmat3(to_world)) < 0.0) {
        std::swap(out.v[1], out.v[2]);
        std::swap(out.normals[1], out.normals[2]);
        std::swap(out.uvs[1], out.uvs[2]);
    }
    return out;
}

// The scene with every instance replaced by its group's placed triangles.
inline Scene flattened_copy(const Scene& scene) {
    Scene out = scene;
    out.shape_groups.clear();
    out.instances.clear();
    for (const Instance& instance : scene.instances)
        for (const Triangle& t : scene.shape_groups[instance.group].triangles)
            out.triangles.push_back(placed_triangle(t, instance.to_world));
    return out;
}

} // namespace wp::test
