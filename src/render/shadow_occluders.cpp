#include "render/shadow_occluders.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

#include "scene/scene_box.hpp"

namespace wp {

namespace {

// -1, 0 or +1: the side of the plane dot(normal, p) == offset that `distance`
// (signed, from it) puts a point on, 0 within `tolerance`.
int side_of(double distance, double tolerance) {
    return distance > tolerance ? 1 : (distance < -tolerance ? -1 : 0);
}

// Whether triangle `t`'s plane has every primitive of the scene on one closed
// side and the eye strictly on that side.
bool is_bounding_face(const Scene& scene, const Triangle& t, double tolerance) {
    const glm::dvec3 cross = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    const double length = glm::length(cross);
    if (!(length > 0.0))
        return false; // no plane (validation refuses such triangles anyway)
    const glm::dvec3 normal = cross / length;
    const double offset = glm::dot(normal, t.v[0]);
    // The side everything lies on, +1 or -1, once something off the plane shows it.
    int side = side_of(glm::dot(normal, scene.camera.eye) - offset, tolerance);
    if (side == 0)
        return false; // the eye on the plane: camera rays may run inside it
    auto on_side = [&](double distance) { return side_of(distance, tolerance) * side >= 0; };
    for (const Triangle& other : scene.triangles)
        for (const glm::dvec3& v : other.v)
            if (!on_side(glm::dot(normal, v) - offset))
                return false;
    for (const Sphere& sphere : scene.spheres) {
        const double d = glm::dot(normal, sphere.center) - offset;
        // The sphere's far point from the plane on the wrong side.
        if (!on_side(side > 0 ? d - sphere.radius : d + sphere.radius))
            return false;
    }
    return true;
}

} // namespace

std::vector<std::uint32_t> shadow_occluders(const Scene& scene) {
    std::vector<std::uint32_t> occluders;
    const bool smooth = std::any_of(scene.triangles.begin(), scene.triangles.end(),
                                    [](const Triangle& t) { return t.has_normals; });
    const double tolerance = 1e-6 * scene_box(scene).largest_coordinate();
    for (std::size_t i = 0; i < scene.triangles.size(); ++i)
        if (smooth || !is_bounding_face(scene, scene.triangles[i], tolerance))
            occluders.push_back(static_cast<std::uint32_t>(i));
    return occluders;
}

} // namespace wp
