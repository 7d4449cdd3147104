#include "render/prepared_scene.hpp"

#include <utility>
#include <vector>

#include "render/wavefront.hpp"

namespace wp {
namespace {

// `release`: the scene's triangles, freed once flattened, or null.
PreparedScene prepare(const Scene& scene, const IntegratorOptions& options, TriangleList* release) {
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
        *release = TriangleList();
    if (hierarchy)
        add_hierarchy(flat, scene.materials);
    prepared.device_scene = std::make_shared<const DeviceScene>(std::move(flat));
    return prepared;
}

// An envmap or a constant emitter: light from every direction a path can
// escape in (kEnvironmentRouletteDepth, integrator_options.hpp, says why that matters).
bool lit_by_environment(const Scene& scene) {
    for (const Emitter& emitter : scene.emitters)
        if (emitter.kind == EmitterKind::Envmap || emitter.kind == EmitterKind::Constant)
            return true;
    return false;
}

} // namespace

// A Mitsuba scene's path integrator, where the command line did not say
// otherwise. hide_emitters leaves out the light a camera ray sees directly:
// the camera path type, which the kernels then track (kernels/path_type.h);
// --path-types may have left out others already. max_depth counts edges, as
// Mitsuba counts them, and so does --max-depth with a Mitsuba file: a number
// that overrides the file's means what the file's means. Its -1 (no limit)
// is wavepath's default, the safety cap. rr_depth is roulette_depth.
// The roulette's rule, unless given, is Mitsuba's where something refracts:
// there a path's radiance is divided by eta^2 as it enters glass, and the
// throughput rule ends such paths for it (docs/performance.md, "Shading and
// roulette"). In a room lit by its own emitters, with no mirror to estimate
// light through, it is the relative rule: the throughput rule ends a path
// at its first bounce with the surface's reflectance, which cuts the
// indirect light of dark walls (1.23x to 1.33x the Cornell bunny's error per
// second by relMSE, the same by MSE: docs/performance.md, "The Cornell
// bunny's relMSE, and two roulette rules"). With mirrors each longer path
// pays next-event estimation through them (the hexroom lost 0.86x to 0.99x
// by MSE), and scenes lit by an environment are unmeasured with it: the
// throughput rule there.
// Where roulette starts, unless given or the file's: later in a scene lit by
// an environment (kEnvironmentRouletteDepth).
IntegratorOptions with_scene_settings(IntegratorOptions options, const Scene& scene) {
    if (options.roulette_rule == RouletteRule::Auto) {
        bool refracts = false, mirrors = false;
        for (const Material& material : scene.materials) {
            refracts = refracts || material.kind == MaterialKind::Dielectric ||
                       material.kind == MaterialKind::RoughDielectric;
            mirrors = mirrors || material.kind == MaterialKind::Mirror;
        }
        if (refracts)
            options.roulette_rule = RouletteRule::Mitsuba;
        else if (!mirrors && !lit_by_environment(scene))
            options.roulette_rule = RouletteRule::Relative;
        else
            options.roulette_rule = RouletteRule::Throughput;
    }
    if (scene.hide_emitters)
        options.path_types &= ~(1u << WP_PATH_TYPE_CAMERA);
    if (scene.mitsuba_depths && options.max_depth_given)
        options.depth_rule = DepthRule::PathLength;
    else if (scene.max_depth > 0 && !options.max_depth_given) {
        options.max_depth = static_cast<std::uint32_t>(scene.max_depth);
        options.depth_rule = DepthRule::PathLength;
    }
    if (scene.rr_depth > 0 && !options.roulette_depth_given)
        options.roulette_depth = scene.rr_depth;
    else if (!options.roulette_depth_given && lit_by_environment(scene))
        options.roulette_depth = kEnvironmentRouletteDepth;
    return options;
}

PreparedScene prepare_scene(const Scene& scene, const IntegratorOptions& options) {
    return prepare(scene, options, nullptr);
}

PreparedScene prepare_scene_releasing_triangles(Scene& scene, const IntegratorOptions& options) {
    return prepare(scene, options, &scene.triangles);
}

} // namespace wp
