#include "scene/instancing.hpp"

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace wp {

void DoubleBox::extend(const glm::dvec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
}

DoubleBox group_box(const ShapeGroup& group) {
    DoubleBox box;
    for (const Triangle& t : group.triangles)
        for (const glm::dvec3& v : t.v)
            box.extend(v);
    return box;
}

DoubleBox mapped_box(const DoubleBox& box, const glm::dmat4& to_world) {
    DoubleBox out;
    if (box.empty())
        return out;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? box.upper.x : box.lower.x,
                           (corner & 2) ? box.upper.y : box.lower.y,
                           (corner & 4) ? box.upper.z : box.lower.z);
        out.extend(glm::dvec3(to_world * glm::dvec4(p, 1.0)));
    }
    return out;
}

std::uint64_t instanced_triangle_count(const Scene& scene) {
    std::uint64_t count = 0;
    for (const Instance& instance : scene.instances)
        count += scene.shape_groups[instance.group].triangles.size();
    return count;
}

std::string instance_transform_problem(const glm::dmat4& to_world) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(to_world[c][r]))
                return "the instance's to_world has a non-finite entry";
    if (to_world[0][3] != 0.0 || to_world[1][3] != 0.0 || to_world[2][3] != 0.0 ||
        to_world[3][3] != 1.0)
        return "the instance's to_world is not affine (its last row must be 0 0 0 1)";
    const glm::dmat3 linear(to_world);
    const double det = glm::determinant(linear);
    // Relative to the columns' lengths, so that a tiny but well-shaped
    // instance is not refused.
    const double scale = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
    if (!(std::abs(det) > 1e-12 * scale))
        return "the instance's to_world is singular (determinant " + std::to_string(det) +
               "): it flattens the shape group";
    const glm::dmat3 inverse = glm::inverse(linear);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(inverse[c][r]))
                return "the instance's to_world has no finite inverse";
    return {};
}

std::string group_material_problem(const ShapeGroup& group,
                                   const std::vector<Material>& materials) {
    for (const Triangle& t : group.triangles)
        if (t.material < materials.size() && materials[t.material].is_emissive())
            return "shape group '" + group.name + "' holds an emitter (material '" +
                   materials[t.material].name +
                   "'); emitters cannot be instanced (as in Mitsuba): place the emitting shape "
                   "outside the group";
    return {};
}

} // namespace wp
