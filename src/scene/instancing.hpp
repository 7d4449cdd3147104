// Shape groups and their instances on the host (scene/scene.hpp has the
// model, kernels/instance.h the device's): their boxes, their counts, and
// the checks every reader applies to them.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace wp {

// An axis-aligned box in double precision; empty when lower > upper.
struct DoubleBox {
    glm::dvec3 lower{std::numeric_limits<double>::infinity()};
    glm::dvec3 upper{-std::numeric_limits<double>::infinity()};
    bool empty() const { return lower.x > upper.x; }
    void extend(const glm::dvec3& p);
};

// The box of a group's vertices, in its object space.
DoubleBox group_box(const ShapeGroup& group);

// The box of `box` mapped by the affine `to_world` (its eight corners').
DoubleBox mapped_box(const DoubleBox& box, const glm::dmat4& to_world);

// How many triangles the instances place: each group's once per instance.
std::uint64_t instanced_triangle_count(const Scene& scene);

// What is wrong with an instance's to_world, in a few words, or "" when it is
// a finite affine map whose linear part has a finite inverse.
std::string instance_transform_problem(const glm::dmat4& to_world);

// What is wrong with a group's materials, or "": an emitting material on one
// of its triangles. Mitsuba refuses emitters in a shape group, and the
// renderer's light tables hold plain triangles only.
std::string group_material_problem(const ShapeGroup& group, const std::vector<Material>& materials);

} // namespace wp
