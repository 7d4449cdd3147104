// The scene flattened into the float32 arrays the kernels read, and the
// features that decide which code the kernels are compiled with.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "wp_shared.h"

namespace wp {

// Which kinds of primitive, material and light the scene uses. Each is a
// preprocessor switch in kernels/features.h.
struct SceneFeatures {
    bool triangles = true;
    bool spheres = true;
    bool diffuse = true;
    bool mirror = true;
    bool lights = true; // emissive triangles for next-event estimation

    static SceneFeatures all() { return {}; }
    // The -D options that compile exactly these features, e.g. "-D WP_HAS_SPHERES=0 ...".
    std::string build_options() const;
    std::string describe() const; // "triangles spheres diffuse mirror lights"
};

SceneFeatures analyse_features(const Scene& scene);

struct DeviceScene {
    std::vector<WpTriangle> triangles;
    std::vector<WpSphere> spheres;
    std::vector<WpMaterial> materials;
    std::vector<WpLight> lights; // emissive triangles with their area CDF
    float light_area = 0.0f;     // total emissive area
    WpCamera camera{};
    int width = 0;
    int height = 0;
};

// Converts to float32 and builds the light table; the camera basis is scaled
// so that film coordinates in [-1, 1] span the field of view.
DeviceScene flatten_scene(const Scene& scene);

} // namespace wp
