#include "app/cli_options.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scene/validate.hpp"

namespace wp {
namespace {

// An option that picks one of `choices` by its name (to_string), stored in
// `value`; its default is value's.
template <typename Enum>
void add_choice(CLI::App& command, const std::string& flag, Enum& value,
                const std::vector<Enum>& choices, const std::string& help) {
    std::map<std::string, Enum> names;
    for (Enum choice : choices)
        names.emplace(to_string(choice), choice);
    std::vector<std::string> allowed;
    for (const auto& [name, choice] : names)
        allowed.push_back(name);
    command
        .add_option_function<std::string>(
            flag, [&value, names](const std::string& name) { value = names.at(name); }, help)
        ->default_str(to_string(value))
        ->check(CLI::IsMember(allowed));
}

// Refuses a --path-types list that parse_path_types does not take.
const CLI::Validator path_type_list(
    [](const std::string& text) -> std::string {
        try {
            parse_path_types(text);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return {};
    },
    "TYPES");

} // namespace

const CLI::Validator finite_number(
    [](const std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
            return "expected a finite number, got '" + text + "'";
        return {};
    },
    "FINITE");

const CLI::Validator positive_finite_number(
    [](const std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value <= 0.0)
            return "expected a positive finite number, got '" + text + "'";
        return {};
    },
    "POSITIVE");

void add_integrator_options(CLI::App& command, IntegratorOptions& options) {
    command.add_option("--seed", options.seed, "Random seed; the same seed gives the same image")
        ->capture_default_str();
    command
        .add_option("--max-depth", options.max_depth,
                    "Safety cap on bounces; Russian roulette ends paths long before it. Paths it "
                    "cuts are counted and reported. With a Mitsuba XML scene it is Mitsuba's "
                    "max_depth and overrides the file's: the longest path in edges, the camera "
                    "ray included (1: emitters seen directly, 2: direct light; "
                    "docs/mitsuba-import.md)")
        ->capture_default_str()
        ->check(CLI::Range(1u, cli_limits::max_depth))
        ->each([&options](const std::string&) { options.max_depth_given = true; });
    command.add_flag("!--no-nee", options.next_event_estimation,
                     "Next-event estimation off: light only from paths that hit an emitter");
    command
        .add_option_function<std::string>(
            "--mirror-nee",
            [&options](const std::string& value) { options.mirror_next_event = value == "on"; },
            "Next-event estimation through planar mirrors and mirror spheres, weighed against "
            "BSDF sampling by multiple importance sampling: 'on' or 'off' (scenes without "
            "mirrors and lights compile none of it; docs/convergence.md)")
        ->default_str(options.mirror_next_event ? "on" : "off")
        ->check(CLI::IsMember({"on", "off"}));
    command
        .add_option_function<std::string>(
            "--shadow-culling",
            [&options](const std::string& value) { options.shadow_culling = value == "on"; },
            "Shadow rays skip the scene's bounding faces (a closed convex room's walls), which "
            "cannot block them: 'on' or 'off' (small scenes only; docs/specialization.md)")
        ->default_str(options.shadow_culling ? "on" : "off")
        ->check(CLI::IsMember({"on", "off"}));
    add_choice(command, "--diffuse", options.diffuse_sampling,
               {DiffuseSampling::Cosine, DiffuseSampling::Report},
               "Lambertian sampling: 'cosine' (cosine-weighted, throughput roulette) or "
               "'report' (the seed report's uniform angles and albedo roulette, made unbiased)");
    add_choice(command, "--mis", options.mis, {MisStrategy::Power, MisStrategy::LightOnly},
               "Light and BSDF samples of the same light: 'power' (weighed by the power "
               "heuristic) or 'light' (light sampling alone where it reaches, to measure what "
               "multiple importance sampling buys; BSDF sampling alone is --no-nee)");
    add_choice(command, "--light-sampling", options.light_sampling,
               {LightSampling::Area, LightSampling::SolidAngle},
               "Next-event estimation: 'area' (uniform on the light) or 'solid-angle' (uniform "
               "in the light's spherical triangles)");
    add_choice(command, "--light-pick", options.light_pick, {LightPick::Power, LightPick::Area},
               "Which emissive triangle next-event estimation picks: 'power' (by area times "
               "the luminance of its radiance, where those differ) or 'area' (by area, the "
               "images of before; docs/lights-and-camera.md)");
    command
        .add_option("--roulette-depth", options.roulette_depth,
                    "The first bounce at which Russian roulette may end a path (1: every "
                    "bounce); before it every path goes on. Default 1, and " +
                        std::to_string(kEnvironmentRouletteDepth) +
                        " in a scene lit by an envmap or constant emitter (docs/performance.md). "
                        "Overrides a Mitsuba file's rr_depth, which counts the same")
        ->capture_default_str()
        ->check(CLI::Range(1u, cli_limits::max_depth))
        ->each([&options](const std::string&) { options.roulette_depth_given = true; });
    add_choice(command, "--roulette", options.roulette_rule,
               {RouletteRule::Auto, RouletteRule::Throughput, RouletteRule::Mitsuba,
                RouletteRule::Sqrt, RouletteRule::Relative},
               "Russian roulette's survival probability: 'throughput' (min(1, max(throughput))), "
               "'mitsuba' (Mitsuba 3's min(0.95, max(throughput) eta^2), eta^2 the squared "
               "indices of refraction the path crossed), 'sqrt' (Blender Cycles' min(1, "
               "sqrt(max(throughput)))), 'relative' (min(1, max(throughput) / max(throughput "
               "after the first bounce))), or 'auto': Mitsuba's where the scene has a "
               "dielectric or roughdielectric, relative where no mirror or environment lights "
               "it, throughput elsewhere (docs/performance.md, \"Shading and roulette\")");
    command
        .add_option_function<std::string>(
            "--path-types",
            [&options](const std::string& list) { options.path_types = parse_path_types(list); },
            "Add only the light of these path types, a comma-separated list of camera, direct, "
            "indirect, mirror, caustic (docs/convergence.md); the parts of one seed sum to the "
            "full image")
        ->default_str("all")
        ->check(path_type_list);
    add_choice(command, "--sampler", options.sampler, {Sampler::Independent, Sampler::Sobol},
               "Random numbers: 'independent' (a hash each) or 'sobol' (a pixel's samples "
               "stratified: Owen-scrambled Sobol points)");
    command.add_flag("--general", options.general_kernels,
                     "Build the all-features kernels instead of the scene's specialised ones");
    add_choice(command, "--traversal", options.traversal,
               {Traversal::Auto, Traversal::Hierarchy, Traversal::Loop},
               "How rays find their hits: 'bvh' (a bounding volume hierarchy), 'loop' (test every "
               "primitive) or 'auto' (the hierarchy past 64 primitives)");
    command.add_flag_function(
        "--regeneration,!--no-regeneration",
        [&options](std::int64_t count) { options.regeneration = count > 0; },
        "Refill the slots of finished paths with new samples at once, keeping queues full "
        "(default: by device, as measured: off on a CPU, one wave of samples at a time; on "
        "elsewhere; `wavepath info` says which; docs/profiling.md, docs/gpu.md)");
    add_choice(command, "--launch-plan", options.launch_plan,
               {LaunchPlan::Auto, LaunchPlan::Stages, LaunchPlan::Bounce, LaunchPlan::Wave},
               "How the stages are launched: 'stages' (a kernel per stage), 'bounce' (intersect, "
               "shade and shadow fused per bounce), 'wave' (one megakernel per wave, no host "
               "round trip per bounce) or 'auto' (per device, as measured; `wavepath info` "
               "says which). The images agree (docs/architecture.md)");
    add_choice(command, "--shade-order", options.shade_order,
               {ShadeOrder::Auto, ShadeOrder::Arrival, ShadeOrder::Sorted},
               "The order shade takes the rays in: 'arrival' (as intersect left them), 'sorted' "
               "(by the kind of material hit; needs the stages launch plan) or 'auto' (per "
               "device, as measured; `wavepath info` says which). The images are the same "
               "(docs/performance.md, \"Shading sorted by material\")");
    command.add_option("--pool", options.pool_size,
                       "Path slots on the device (default: one per pixel); fewer use less memory");
    options.self_check = true;
    command.add_flag_callback(
        "--no-self-check", [&options] { options.self_check = false; },
        "Skip the check of the specialised kernels against the general ones on a device, driver "
        "and build options not met before (docs/gpu.md; same as WAVEPATH_SELF_CHECK=0)");
    command.add_flag_callback(
        "--no-cache", [&options] { options.program_cache = CachePolicy::off(); },
        "Build the kernels from source; neither read nor write the program cache "
        "(~/.cache/wavepath; same as WAVEPATH_NO_CACHE=1)");
}

void add_device_option(CLI::App& command, std::string& device) {
    command.add_option("--device,-d", device,
                       "OpenCL device: an index P:D from `wavepath devices`, or part of its name "
                       "(default: $WAVEPATH_DEVICE, else first GPU, else first CPU)");
}

void add_device_list_option(CLI::App& command, std::string& devices) {
    command.add_option("--device,-d", devices,
                       "OpenCL devices: an index P:D from `wavepath devices` or part of a name, "
                       "a comma-separated list of them (0:0,1:0) or 'all'; several devices "
                       "share the samples (default: $WAVEPATH_DEVICE, else first GPU, else "
                       "first CPU)");
}

namespace {

// One command runs per process, so its -D values and --lenient can live here
// rather than in each command's struct, where every loader call would have
// to pass them.
SceneReadOptions& read_options() {
    static SceneReadOptions values;
    return values;
}

} // namespace

void add_scene_options(CLI::App& command) {
    command
        .add_option_function<std::vector<std::string>>(
            "-D,--define",
            [](const std::vector<std::string>& given) {
                for (const std::string& text : given) {
                    const std::size_t equals = text.find('=');
                    read_options().defines[text.substr(0, equals)] = text.substr(equals + 1);
                }
            },
            "name=value: sets $name in a Mitsuba XML scene, as Mitsuba's -D does (over the "
            "file's <default>); repeatable")
        ->check([](const std::string& text) -> std::string {
            const std::size_t equals = text.find('=');
            if (equals == std::string::npos || equals == 0)
                return "expected name=value, got '" + text + "'";
            return "";
        });
    command.add_flag_callback(
        "--lenient", [] { read_options().lenient = true; },
        "a Mitsuba XML scene: render a BSDF wavepath cannot read as a grey diffuse, and leave "
        "out shapes, emitters and integrators of plugins it has not, each with a warning "
        "(docs/mitsuba-import.md)");
}

const SceneReadOptions& scene_read_options() {
    return read_options();
}

void add_image_size_options(CLI::App& command, int& width, int& height) {
    const auto size = CLI::Range(1, scene_limits::max_resolution);
    command.add_option("--width", width, "Image width (default: the scene's)")->check(size);
    command.add_option("--height", height, "Image height (default: the scene's)")->check(size);
}

} // namespace wp
