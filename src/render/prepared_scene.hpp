// A scene prepared for rendering: what every device of a render shares.
//
// The features the integrator gives the scene under its options, and the
// scene flattened to float32 with its hierarchy, depend on the scene and
// the options alone, not on a device. They are made once per render and
// every device's WavefrontIntegrator uploads the same arrays (a render on N
// devices builds one hierarchy, not N: docs/multi-device.md). A device that
// shares the host's memory (PoCL's CPU device) makes its scene buffers over
// the arrays in place, and they hold the arrays as long as they live; a
// device that copies them keeps nothing, and the host's copy then lives only
// as long as the caller holds it (render/device_buffers.hpp).
#pragma once

#include <cstdint>
#include <memory>

#include "render/device_scene.hpp"
#include "render/integrator_options.hpp"
#include "scene/scene.hpp"

namespace wp {

struct PreparedScene {
    // The caller's options with the scene's own settings (hide_emitters
    // leaves out the camera path type).
    IntegratorOptions options;
    SceneFeatures features; // integrator_features(scene, options)
    // Shared, not copied, by a prepared scene's copies (the self-check's
    // tile views the same arrays at another resolution).
    std::shared_ptr<const DeviceScene> device_scene;
    // The pixels rendered: the camera's, or a tile's (the same view).
    int width = 0;
    int height = 0;
};

// `options` with the scene's own settings where the command line gave none:
// a Mitsuba file's path integrator (max_depth, rr_depth, hide_emitters).
// What prepare_scene renders with, and what `kernel-source` prints.
IntegratorOptions with_scene_settings(IntegratorOptions options, const Scene& scene);

// Prepares `scene` for `options`; throws what integrator_features and
// flatten_scene throw (e.g. --traversal loop on a scene with instances).
PreparedScene prepare_scene(const Scene& scene, const IntegratorOptions& options);

// The same, freeing scene.triangles (capacity included) as soon as they are
// flattened, before the hierarchy is built: for a caller that has no more
// use for them, so that a big mesh's double-precision triangles and the
// hierarchy's build are never in memory together (docs/meshes.md, "Host
// memory of a big mesh"). The rest of the scene is left as it was.
PreparedScene prepare_scene_releasing_triangles(Scene& scene, const IntegratorOptions& options);

} // namespace wp
