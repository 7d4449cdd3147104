#include "render/prepared_scene.hpp"

#include <utility>
#include <vector>

#include "render/wavefront.hpp"

namespace wp {
namespace {

// A scene with hide_emitters (Mitsuba's) leaves out the light a camera ray
// sees directly: the camera path type, which the kernels then track
// (kernels/path_type.h); --path-types may have left out others already.
IntegratorOptions with_scene_settings(IntegratorOptions options, const Scene& scene) {
    if (scene.hide_emitters)
        options.path_types &= ~(1u << WP_PATH_TYPE_CAMERA);
    return options;
}

// `release`: the scene's triangles, freed once flattened, or null.
PreparedScene prepare(const Scene& scene, const IntegratorOptions& options,
                      std::vector<Triangle>* release) {
    PreparedScene prepared;
    prepared.options = with_scene_settings(options, scene);
    prepared.features = integrator_features(scene, prepared.options);
    prepared.width = scene.camera.width;
    prepared.height = scene.camera.height;
    // The compiled features' hierarchy is the scene's, --general or not
    // (SceneFeatures::general_for), and so are the flattened arrays.
    const bool hierarchy = prepared.features.bvh;
    DeviceScene flat = flatten_without_hierarchy(scene, hierarchy, prepared.options.light_pick);
    if (release)
        std::vector<Triangle>().swap(*release);
    if (hierarchy)
        add_hierarchy(flat, scene.materials);
    prepared.device_scene = std::make_shared<const DeviceScene>(std::move(flat));
    return prepared;
}

} // namespace

PreparedScene prepare_scene(const Scene& scene, const IntegratorOptions& options) {
    return prepare(scene, options, nullptr);
}

PreparedScene prepare_scene_releasing_triangles(Scene& scene, const IntegratorOptions& options) {
    return prepare(scene, options, &scene.triangles);
}

} // namespace wp
