// The box around everything a render sees of a scene: triangle vertices,
// spheres and the camera's eye. Its size and its distance from the origin
// decide how float32 rendering must treat the scene (render/float_range.hpp)
// and what it cannot render (scene/validate.hpp).
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace wp {

struct SceneBox {
    glm::dvec3 lower{0.0};
    glm::dvec3 upper{0.0};

    glm::dvec3 centre() const { return 0.5 * (lower + upper); }
    double size() const;               // the longest side
    double largest_coordinate() const; // the largest magnitude of a corner's component
};

SceneBox scene_box(const Scene& scene);

} // namespace wp
