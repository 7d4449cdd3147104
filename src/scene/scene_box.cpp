#include "scene/scene_box.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "scene/instancing.hpp"

namespace wp {

double SceneBox::size() const {
    const glm::dvec3 d = upper - lower;
    return std::max({d.x, d.y, d.z});
}

double SceneBox::largest_coordinate() const {
    const glm::dvec3 a = glm::max(glm::abs(lower), glm::abs(upper));
    return std::max({a.x, a.y, a.z});
}

SceneBox scene_box(const Scene& scene) {
    SceneBox box{scene.camera.eye, scene.camera.eye};
    auto add = [&box](const glm::dvec3& p) {
        box.lower = glm::min(box.lower, p);
        box.upper = glm::max(box.upper, p);
    };
    for (const Triangle& t : scene.triangles)
        for (const glm::dvec3& v : t.v)
            add(v);
    for (const Sphere& s : scene.spheres) {
        add(s.center - glm::dvec3(s.radius));
        add(s.center + glm::dvec3(s.radius));
    }
    std::vector<DoubleBox> groups;
    for (const ShapeGroup& g : scene.shape_groups)
        groups.push_back(group_box(g));
    for (const Instance& instance : scene.instances) {
        const DoubleBox b = mapped_box(groups[instance.group], instance.to_world);
        if (!b.empty()) {
            add(b.lower);
            add(b.upper);
        }
    }
    return box;
}

} // namespace wp
