// What a render asks of the wavefront integrator: the seed, the estimator
// variant, the kernels to build and how, and how paths are scheduled. One
// struct, so that every command that renders (app/integrator_cli.cpp) and
// every test sets the same things the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cl/program_cache.hpp"
#include "render/light_pick.hpp"
#include "wp_shared.h" // WP_PATH_TYPE_*

namespace wp {

// Estimator variants (kernels/estimator.h; compared in docs/convergence.md).
// How a Lambertian bounce picks its next direction, and how paths end:
enum class DiffuseSampling {
    Cosine, // cosine-weighted directions, throughput roulette
    Report, // the student report's: uniform (theta, phi), albedo roulette
};
// How next-event estimation picks a point on a light triangle:
enum class LightSampling {
    Area,       // uniform by area
    SolidAngle, // uniform in the subtended solid angle (spherical triangles)
};

// The survival probability of the throughput roulette (kernels/estimator.h,
// WP_ROULETTE_RULE; measured in docs/performance.md, "Shading and roulette"):
enum class RouletteRule {
    Auto,       // Mitsuba's where the scene refracts (a dielectric or roughdielectric;
                // measured 2.1x the error per second by MSE on the material-rich
                // showcase), relative where nothing refracts and no mirror or
                // environment lights it (1.23x-1.33x by relMSE on the Cornell bunny),
                // throughput elsewhere (with_scene_settings). Left unresolved, as
                // throughput.
    Throughput, // min(1, max(throughput))
    Mitsuba,    // Mitsuba 3's: min(0.95, max(throughput) eta^2), eta^2 the squared
                // relative indices of refraction the path crossed
    Sqrt,       // Blender Cycles': min(1, sqrt(max(throughput))): gentler on paths
                // whose throughput has fallen, which carry a dark pixel's light
    Relative,   // min(1, max(throughput) / max(throughput after the first bounce))
};

// How a light sample and a BSDF sample that could find the same light are
// weighed at a glossy vertex (and at every vertex for the environment):
enum class MisStrategy {
    Power,     // the power heuristic (the estimator)
    LightOnly, // light sampling alone wherever it reaches: a BSDF sample's hit on a
               // light it could have sampled counts 0 (for measuring what MIS buys;
               // BSDF sampling alone is --no-nee)
};

// Where the random numbers come from (kernels/rng.h; compared in
// docs/convergence.md, "Samplers"). Both are pure functions of (seed, pixel,
// sample, bounce, dimension), so neither depends on how samples are split.
enum class Sampler {
    Independent, // every number an independent hash
    Sobol,       // a pixel's samples stratified: Owen-scrambled Sobol pairs (kernels/sobol.h)
};

// How rays find what they hit:
enum class Traversal {
    Auto,      // a bounding volume hierarchy past kMinBvhPrimitives, else every primitive
    Hierarchy, // always the hierarchy
    Loop,      // always every primitive (the images agree; only the speed differs)
};

// What max_depth counts (docs/mitsuba-import.md, "max_depth"):
enum class DepthRule {
    Bounces,    // wavepath's safety cap: at most max_depth bounces; the last vertex
                // still samples a light, and the paths it cuts are counted
    PathLength, // Mitsuba's max_depth: paths of at most max_depth edges, the camera ray
                // included; the vertex at the last edge adds its emission and ends
                // the path (no light sample there, no bounce: kernels/shade.cl)
};

// How the stages are launched (docs/architecture.md, "Launch plans"). Every
// plan runs the same stage functions in the same order per path, so the
// images agree (tests/render/test_launch_plans.cpp says how closely).
enum class LaunchPlan {
    Auto,   // chosen per device by measurement (choose_launch_plan, wavefront.hpp)
    Stages, // one kernel per stage, a host synchronisation per bounce
    Bounce, // intersect, shade and shadow fused: one kernel per bounce
    Wave,   // one megakernel per wave: each work-item runs its slot's whole paths
};

// The order in which the stages plan's shade kernel takes the rays
// (kernels/shade_sort.cl). Every order gives the same image, bit for bit.
enum class ShadeOrder {
    Auto,    // chosen per device by measurement (choose_launch_plan, wavefront.hpp)
    Arrival, // as intersect left the queue
    Sorted,  // sorted by the kind of material each ray hit (a counting sort before shade)
};

// Every path type (kernels/path_type.h): the full estimate.
inline constexpr std::uint32_t kAllPathTypes = (1u << WP_PATH_TYPE_COUNT) - 1u;

// Where roulette starts in a scene lit by an environment (an envmap or a
// constant emitter): such a scene is open, so paths end by escaping, and
// roulette from the first bounce saves little work (on the showcase 1.29x
// the rays without it until bounce 8) while multiplying the rare bright
// paths of its survivors (1/q on dark surfaces): there roulette from 1 has
// 2.0x the relMSE and 1.65x the MSE per sample of roulette from 8
// (docs/performance.md, "Why relMSE lags Mitsuba's"). Closed rooms keep 1:
// on the hexroom and the bunny later starts measured worse by MSE.
inline constexpr std::uint32_t kEnvironmentRouletteDepth = 8;

struct IntegratorOptions {
    std::uint32_t seed = 0;
    // Safety cap on bounces. Russian roulette ends paths long before it in
    // any scene with absorption; it exists for lossless mirror corridors. The
    // number of paths it cuts is counted in RenderStats::capped_paths.
    std::uint32_t max_depth = 1024;
    DepthRule depth_rule = DepthRule::Bounces;
    // Whether the command line gave max_depth and roulette_depth: a scene's
    // own (a Mitsuba file's max_depth and rr_depth) then gives way to them
    // (prepare_scene).
    bool max_depth_given = false;
    bool roulette_depth_given = false;
    bool general_kernels = false; // compile every feature, not just the scene's
    Traversal traversal = Traversal::Auto;
    // Start rays from the smooth surface that vertex normals describe, not the
    // flat triangle (Hanika 2021; kernels/primitive.h). Off only to show the
    // artefact it removes.
    bool shadow_terminator_fix = true;
    // Next-event estimation: one shadow ray to a light per diffuse hit. Off,
    // light is found only by paths that hit emitters.
    bool next_event_estimation = true;
    // Next-event estimation through planar mirrors as well (kernels/mirror_light.h),
    // weighed against BSDF sampling by multiple importance sampling; compiled
    // only for scenes with planar mirrors and lights (--mirror-nee on|off).
    bool mirror_next_event = true;
    // Shadow rays skip the scene's bounding faces, which cannot block them
    // (render/shadow_occluders.hpp); with fixed counts only. The images agree
    // up to the rounding cases that file names (--shadow-culling on|off).
    bool shadow_culling = true;
    // The defaults are the most efficient variant measured on the hexroom
    // (docs/convergence.md); solid-angle light sampling wins by an order of
    // magnitude where surfaces come close to a light.
    DiffuseSampling diffuse_sampling = DiffuseSampling::Cosine;
    LightSampling light_sampling = LightSampling::Area;
    // Which emissive triangle next-event estimation picks: by power where their
    // luminances differ (render/light_pick.hpp), or by area (--light-pick).
    LightPick light_pick = LightPick::Power;
    MisStrategy mis = MisStrategy::Power;
    // The first bounce at which throughput roulette may end a path (1: every
    // bounce); before it paths always go on (kernels/estimator.h). Unless
    // given (roulette_depth_given) or a Mitsuba file's rr_depth, a scene lit
    // by an environment starts it at kEnvironmentRouletteDepth instead
    // (with_scene_settings).
    std::uint32_t roulette_depth = 1;
    // How the roulette weighs a path (--roulette). Mitsuba's, Cycles' and the
    // relative rule compile the kernels with WP_ROULETTE_RULE=1, 2 and 3; the
    // throughput rule adds no option.
    RouletteRule roulette_rule = RouletteRule::Auto;
    // The path types whose light the render adds, a set of 1 << WP_PATH_TYPE_*
    // (kernels/path_type.h). Anything but all of them compiles the kernels
    // with WP_PATH_TYPES, one program for every such set (the set itself is
    // WpFrame.path_types): a part of the image, for measuring where the
    // error is (docs/convergence.md).
    std::uint32_t path_types = kAllPathTypes;
    // Stratified samples by default: on the hexroom at 64 spp they cut the
    // MSE by 40 % (by 11x next to the light's edges; docs/convergence.md,
    // "Samplers").
    Sampler sampler = Sampler::Sobol;
    // Refill finished slots with new samples at once, instead of waiting for
    // the whole pool to finish (a "wave") before generating again. Unset:
    // by device (choose_launch_plan, render/wavefront.hpp): off on a CPU
    // device, where PoCL was measured 30-40 % slower with it (camera rays of
    // scattered pixels lose the coherence SIMD lanes rely on; see
    // docs/profiling.md), on elsewhere: it keeps launches full, which is what
    // a GPU needs (3.5x on the H200, docs/gpu.md).
    std::optional<bool> regeneration;
    // Path slots; 0 means one per pixel. Fewer save device memory (the
    // per-slot rows of WP_PATH_BUFFERS, path_buffer_bytes() in
    // render/device_buffers.hpp) at some cost in parallelism.
    std::uint32_t pool_size = 0;
    LaunchPlan launch_plan = LaunchPlan::Auto;
    // The stages and bounce plans without regeneration: once a wave has at
    // most this many rays left, the tail kernel (kernels/tail.cl) traces its
    // paths on in one launch (another where they cross a fold of the film)
    // instead of a launch of every stage and a host sync per bounce; the
    // image is the same bit for bit. Unset: kDefaultTailRays, at most a
    // sixteenth of the pool (tail_rays_for, render/wavefront.hpp). 0: never.
    // WAVEPATH_TAIL_RAYS overrides either (for measuring).
    std::optional<std::uint32_t> tail_rays;
    // Sorted needs the stages plan (a fused kernel shades each ray in the
    // work-item that traced it): it makes `auto` pick that plan.
    ShadeOrder shade_order = ShadeOrder::Auto;
    // Check the specialised kernels against the general ones the first time
    // a device, driver and build options meet, and build the general ones if
    // they disagree (render/self_check.hpp). Off here, so that tests and
    // library users opt in; every command that renders turns it on
    // (--no-self-check turns it off; WAVEPATH_SELF_CHECK=0 too).
    bool self_check = false;
    // Whether the kernel build reads and writes the on-disk program cache,
    // and where. The default follows the environment (WAVEPATH_NO_CACHE,
    // WAVEPATH_CACHE_DIR) as it is when the options are made; `--no-cache`
    // sets it off here instead of changing the environment of the process.
    CachePolicy program_cache = CachePolicy::from_environment();
    // The AOVs to gather (a set of kAov* bits; --aov): the camera ray's first
    // hit per pixel, summed beside the film (Film::aov_mean). Any compiles
    // the kernels with WP_AOV; none (the default) compiles no AOV code.
    std::uint32_t aovs = 0;
};

// The AOVs (docs/lights-and-camera.md, "AOVs"), in the order --aov names
// them and the EXR's layers are made.
inline constexpr std::uint32_t kAovAlbedo = 1u; // the first hit's material albedo, rgb
inline constexpr std::uint32_t kAovNormal = 2u; // its shading normal facing the camera, xyz
inline constexpr std::uint32_t kAovDepth = 4u;  // the distance along the camera ray to it
inline constexpr std::uint32_t kAovCount = 3u;
// "albedo", "normal", "depth" for AOV number 0, 1, 2 (bit 1 << number).
std::string aov_name(std::uint32_t number);
// A set of AOVs from a comma-separated list of those names; throws
// std::invalid_argument for an empty list or entry, an unknown name or one
// named twice.
std::uint32_t parse_aovs(const std::string& list);
// The names of a set, comma-separated, in AOV order ("" for none).
std::string describe_aovs(std::uint32_t aovs);

// The variants' names, as the command line takes them and reports print
// them: "cosine" and "report"; "area" and "solid-angle".
std::string to_string(DiffuseSampling sampling);
std::string to_string(LightSampling sampling);
std::string to_string(MisStrategy strategy);
std::string to_string(RouletteRule rule);   // "throughput", "mitsuba"
std::string to_string(Traversal traversal); // "auto", "bvh", "loop"
std::string to_string(Sampler sampler);     // "independent", "sobol"
std::string to_string(LaunchPlan plan);     // "auto", "stages", "bounce", "wave"
std::string to_string(ShadeOrder order);    // "auto", "arrival", "sorted"

// The path types' names, in WP_PATH_TYPE_* order: "camera", "direct",
// "indirect", "mirror", "caustic".
std::string path_type_name(std::uint32_t type);
// A set of path types from a comma-separated list of those names, or "all";
// throws std::invalid_argument naming a bad or empty entry.
std::uint32_t parse_path_types(const std::string& list);
// The names of a set, comma-separated ("all" for every type).
std::string describe_path_types(std::uint32_t types);

// A short name for an estimator, e.g. "cosine+nee+solid-angle", "report+no-nee".
// (Light sampling is left out without next-event estimation: it does not apply.)
// The area light pick adds "+area-pick"; a roulette depth other than the
// default "+roulette-from-N", Mitsuba's roulette rule "+roulette-mitsuba", a subset
// of the path types "+paths=direct,caustic", Mitsuba's max_depth M "+path-length-M".
std::string describe_estimator(const IntegratorOptions& options);

} // namespace wp
