// `wavepath info`: what a scene contains, which kernels it gets, and what
// building them costs (docs/specialization.md); or, given an image, how the
// image was made (its metadata, docs/images-and-metadata.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "cl/context.hpp"
#include "cl/device.hpp"
#include "cl/error.hpp"
#include "cl/program.hpp"
#include "cl/stages.hpp"
#include "image/image_io.hpp"
#include "render/device_scene.hpp"
#include "render/prepared_scene.hpp"
#include "render/wavefront.hpp"
#include "scene/instancing.hpp"
#include "scene/load.hpp"
#include "util/file.hpp"

namespace wp {
namespace {

// What the geometry takes on the device: the primitives and, with one, the
// hierarchy (its build too).
void print_geometry_memory(const DeviceScene& scene) {
    const std::size_t primitive_bytes =
        scene.triangles.size() * sizeof(WpTriangle) + scene.spheres.size() * sizeof(WpSphere);
    const std::size_t hierarchy_bytes = scene.bvh_nodes.size() * sizeof(WpBvhNode);
    if (!scene.bvh_nodes.empty()) {
        const BvhStats& b = scene.bvh_stats;
        std::printf("hierarchy: %u nodes (%u leaves, at most %u primitives), depth %u, SAH cost "
                    "%.1f, built in %.3f s\n",
                    b.nodes, b.leaves, b.largest_leaf, b.depth, b.sah_cost, b.build_seconds);
    }
    std::printf("geometry on the device: %.1f MB primitives + %.1f MB hierarchy",
                1e-6 * double(primitive_bytes), 1e-6 * double(hierarchy_bytes));
    if (!scene.triangles.empty())
        std::printf(" = %.1f bytes per triangle",
                    double(primitive_bytes + hierarchy_bytes) / double(scene.triangles.size()));
    std::printf("\n");
    if (!scene.instances.empty()) {
        // Each group's triangles and hierarchy once, and a record per instance.
        const std::size_t group_bytes = scene.group_triangles.size() * sizeof(WpTriangle) +
                                        scene.group_bvh_nodes.size() * sizeof(WpBvhNode);
        const std::size_t instance_bytes = scene.instances.size() * sizeof(WpInstance);
        const std::uint64_t placed = scene.instanced_triangles;
        std::printf("instances on the device: %.1f MB shape groups (%zu triangles, %zu nodes) + "
                    "%.1f MB for %zu instances, placing %llu triangles = %.3g bytes per placed "
                    "triangle\n",
                    1e-6 * double(group_bytes), scene.group_triangles.size(),
                    scene.group_bvh_nodes.size(), 1e-6 * double(instance_bytes),
                    scene.instances.size(), static_cast<unsigned long long>(placed),
                    double(group_bytes + instance_bytes) / double(placed));
    }
}

// Launches use this work-group size, as the integrator's do, so that a driver
// that compiles per work-group size (PoCL) compiles what a render will use.
constexpr std::size_t kLaunchGroup = 64;

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format_seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, s < 0.1 ? "%.4f s" : "%.3f s", s);
    return text;
}

std::string format_bytes(std::uint64_t bytes) {
    return std::to_string(bytes) + " B";
}

// What the driver reports of one kernel, and how long its first launch took.
struct KernelReport {
    std::string name;
    double first_launch = -1.0; // < 0: could not be launched (see why)
    std::string why;
    std::size_t work_group_size = 0;
    std::size_t preferred_multiple = 0;
    std::uint64_t private_bytes = 0;
    std::uint64_t local_bytes = 0;
    bool have_attributes = false;
};

// How to fill each argument of a kernel for a launch that does no work.
enum class ArgumentKind { Buffer, Local, Frame, Scalar };

// The argument kinds of a kernel from its argument info (which needs a
// program built with -cl-kernel-arg-info); empty with `why` set if unknown.
std::vector<ArgumentKind> argument_kinds(const cl::Kernel& kernel, std::string& why) {
    std::vector<ArgumentKind> kinds;
    cl_uint arguments = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
    for (cl_uint i = 0; i < arguments; ++i) {
        cl_kernel_arg_address_qualifier space = 0;
        std::string type;
        try {
            space = kernel.getArgInfo<CL_KERNEL_ARG_ADDRESS_QUALIFIER>(i);
            type = kernel.getArgInfo<CL_KERNEL_ARG_TYPE_NAME>(i);
        } catch (const cl::Error&) {
            why = "the driver gives no argument types";
            return {};
        }
        type.erase(std::find(type.begin(), type.end(), '\0'), type.end());
        if (space == CL_KERNEL_ARG_ADDRESS_GLOBAL || space == CL_KERNEL_ARG_ADDRESS_CONSTANT)
            kinds.push_back(ArgumentKind::Buffer);
        else if (space == CL_KERNEL_ARG_ADDRESS_LOCAL)
            kinds.push_back(ArgumentKind::Local);
        else if (type == "WpFrame")
            kinds.push_back(ArgumentKind::Frame);
        else if (type == "uint" || type == "wp_uint" || type == "int" || type == "float")
            kinds.push_back(ArgumentKind::Scalar);
        else {
            why = "argument " + std::to_string(i) + " has type '" + type + "'";
            return {};
        }
    }
    return kinds;
}

// Times one launch of `kernel` that does no work: every buffer argument is a
// zero-filled dummy and every scalar or struct argument zero, and the
// wavefront kernels return at once when their item count is zero. The time
// is then the driver's deferred compilation, if it has one (PoCL compiles
// each kernel for its work-group size when first launched).
double time_empty_launch(DeviceContext& device, cl::Kernel& kernel,
                         const std::vector<ArgumentKind>& kinds) {
    static const std::vector<unsigned char> zeros(4096, 0);
    cl::Buffer dummy(device.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, zeros.size(),
                     const_cast<unsigned char*>(zeros.data()));
    for (cl_uint i = 0; i < kinds.size(); ++i) {
        switch (kinds[i]) {
        case ArgumentKind::Buffer:
            kernel.setArg(i, dummy);
            break;
        case ArgumentKind::Local:
            kernel.setArg(i, cl::Local(16));
            break;
        case ArgumentKind::Frame:
            kernel.setArg(i, sizeof(WpFrame), zeros.data());
            break;
        case ArgumentKind::Scalar:
            kernel.setArg(i, 4, zeros.data());
            break;
        }
    }
    std::size_t group = std::min(kLaunchGroup, device.info.max_work_group_size);
    device.queue.finish();
    auto start = std::chrono::steady_clock::now();
    device.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(group),
                                      cl::NDRange(group));
    device.queue.finish();
    return seconds_since(start);
}

// Attributes and first-launch time of every stage of `program`; `arguments`
// holds each stage's argument kinds (from a program with argument info).
std::vector<KernelReport> report_kernels(DeviceContext& device, const cl::Program& program,
                                         const std::vector<std::vector<ArgumentKind>>& arguments,
                                         const std::vector<std::string>& unknown) {
    std::vector<KernelReport> reports;
    for (std::size_t k = 0; k < kStageKernelNames.size(); ++k) {
        KernelReport r;
        r.name = std::string(kStageKernelNames[k]);
        cl::Kernel kernel(program, r.name.c_str());
        const cl::Device& d = device.info.device;
        try {
            r.work_group_size = kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(d);
            r.preferred_multiple =
                kernel.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(d);
            r.private_bytes = kernel.getWorkGroupInfo<CL_KERNEL_PRIVATE_MEM_SIZE>(d);
            r.local_bytes = kernel.getWorkGroupInfo<CL_KERNEL_LOCAL_MEM_SIZE>(d);
            r.have_attributes = true;
        } catch (const cl::Error&) {
        }
        r.why = unknown[k];
        if (r.why.empty()) {
            try {
                r.first_launch = time_empty_launch(device, kernel, arguments[k]);
            } catch (const cl::Error& e) {
                r.why = describe_cl_error(e);
            }
        }
        reports.push_back(r);
    }
    return reports;
}

double triangle_area(const Triangle& t) {
    return 0.5 * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
}

void print_scene(const std::string& path, const Scene& scene) {
    std::size_t kinds[3] = {0, 0, 0}, emissive_materials = 0;
    for (const Material& m : scene.materials) {
        std::size_t kind = static_cast<std::size_t>(m.kind);
        if (kind < 3)
            ++kinds[kind];
        emissive_materials += m.is_emissive();
    }
    std::size_t emissive = 0;
    double light_area = 0.0;
    for (const Triangle& t : scene.triangles)
        if (scene.materials[t.material].is_emissive()) {
            ++emissive;
            light_area += triangle_area(t);
        }
    std::printf("scene: %s\n", path.c_str());
    std::printf("  primitives: %zu triangles, %zu spheres\n", scene.triangles.size(),
                scene.spheres.size());
    if (!scene.instances.empty()) {
        std::size_t defined = 0;
        for (const ShapeGroup& g : scene.shape_groups)
            defined += g.triangles.size();
        std::printf("  instances: %zu of %zu shape groups (%zu triangles defined once, %llu "
                    "placed)\n",
                    scene.instances.size(), scene.shape_groups.size(), defined,
                    static_cast<unsigned long long>(instanced_triangle_count(scene)));
    }
    std::printf("  materials: %zu (%zu diffuse, %zu mirror, %zu emitter; %zu emissive)\n",
                scene.materials.size(), kinds[0], kinds[1], kinds[2], emissive_materials);
    std::printf("  lights: %zu emissive triangles, total area %.6g\n", emissive, light_area);
    for (const Emitter& e : scene.emitters) {
        std::printf("  emitter: %s", emitter_kind_name(e.kind));
        if (e.image) {
            // As the device holds it: padded to 2x3 at least, float RGB
            // texels and a float table entry a patch (lights/envmap.h).
            const std::size_t w = std::max(e.image->width, 2u), h = std::max(e.image->height, 3u);
            std::printf(" %s, %ux%u texels, %.1f MB on the device", e.filename.c_str(),
                        e.image->width, e.image->height,
                        1e-6 * double(12 * w * h + 4 * ((h - 1) * (w + 1))));
        }
        std::printf("\n");
    }
    std::printf("  camera: %dx%d\n", scene.camera.width, scene.camera.height);
    if (!scene.textures.empty()) {
        // Texels as the device holds them (8-bit files 4 bytes a texel, HDR
        // and EXR 12), counted once per file however often it is named.
        std::set<const TextureImage*> images;
        std::size_t bytes = 0, bitmaps = 0;
        for (const Texture& t : scene.textures)
            if (t.image) {
                ++bitmaps;
                if (images.insert(t.image.get()).second)
                    bytes += t.image->bytes();
            }
        std::printf("  textures: %zu (%zu bitmaps from %zu files, %.1f MB of texels)\n",
                    scene.textures.size(), bitmaps, images.size(), 1e-6 * double(bytes));
    }
    for (const std::string& warning : scene.warnings)
        std::printf("  warning: %s\n", warning.c_str());
}

bool is_image_path(const std::string& path) {
    const std::string ext = lower_extension(path);
    return ext == ".exr" || ext == ".png" || ext == ".pfm";
}

// An image's format, size and metadata, one entry a line.
int print_image_info(const std::string& path) {
    const ImageSummary summary = read_image_summary(path);
    std::printf("image: %s (%s, %dx%d)\n", path.c_str(), summary.format.c_str(), summary.width,
                summary.height);
    if (!summary.has_metadata_place) {
        std::printf("metadata: none (%s files have no place for it)\n", summary.format.c_str());
        return 0;
    }
    if (summary.metadata.empty()) {
        std::printf("metadata: none\n");
        return 0;
    }
    std::size_t width = 0;
    for (const auto& entry : summary.metadata)
        width = std::max(width, entry.first.size());
    std::printf("metadata:\n");
    for (const auto& [name, text] : summary.metadata)
        std::printf("  %-*s  %s\n", static_cast<int>(width), name.c_str(), text.c_str());
    return 0;
}

} // namespace

CLI::App* add_info_subcommand(CLI::App& app, InfoCommand& command) {
    CLI::App* i = app.add_subcommand(
        "info", "Print a scene's counts, its kernel features and build options, each build's "
                "time cold and cached, and what the driver reports of each kernel; or an "
                "image's metadata (how it was made)");
    i->add_option("scene", command.scene,
                  "Scene file (JSON), or an image (.exr, .png, .pfm) whose metadata to print")
        ->required();
    add_scene_options(*i);
    add_device_option(*i, command.device);
    // All of them, since the estimator's options are build options too.
    add_integrator_options(*i, command.integrator);
    return i;
}

CLI::App* add_kernel_source_subcommand(CLI::App& app, KernelSourceCommand& command) {
    CLI::App* k = app.add_subcommand(
        "kernel-source", "Print the kernel build options of a scene; write the expanded source");
    k->group(""); // hidden: a tool for scripts (.ci/gpu-targets-check), not for users
    k->add_option("scene", command.scene, "Scene file (JSON)")->required();
    add_scene_options(*k);
    k->add_option("--source", command.source,
                  "Write the program text, every #include expanded as the host does");
    add_integrator_options(*k, command.integrator);
    return k;
}

int run_kernel_source(const KernelSourceCommand& command) {
    check_output(command.source);
    const Scene scene = load_scene(command.scene, scene_read_options());
    const IntegratorOptions options = with_scene_settings(command.integrator, scene);
    const SceneFeatures compiled = compiled_features(integrator_features(scene, options), options);
    if (!command.source.empty()) {
        const std::string text = expand_includes(wavefront_program_source(), "wavefront.cl");
        write_bytes_atomically(command.source, text.data(), text.size());
    }
    std::printf("%s\n", kernel_build_options(compiled, options).c_str());
    return 0;
}

int run_info(const InfoCommand& command) {
    if (is_image_path(command.scene))
        return print_image_info(command.scene);
    Scene scene = load_scene(command.scene, scene_read_options());
    print_scene(command.scene, scene);

    DeviceContext device(select_device(command.device));
    std::printf("device: %s (%s, driver %s)\n", device.info.name.c_str(),
                device.info.platform_name.c_str(), device.info.driver_version.c_str());

    // The first build in a process pays for starting the compiler (PoCL
    // loads its kernel library); a trivial one here keeps that out of the
    // figures below and reports it on its own.
    std::random_device entropy;
    BuiltProgram warm_up = build_program(
        device.context, device.info.device, "__kernel void wp_info_warm_up(void) {}", "warm_up.cl",
        "-D WP_INFO_WARM_UP=" + std::to_string(entropy()), CachePolicy::off());

    // The scene prepared as a render prepares it (a tiny image: the options
    // do not depend on the resolution): its features, its arrays and its
    // hierarchy, made once and read here and by the integrator. The scene's
    // triangles, printed above, are freed once flattened.
    scene.camera.width = scene.camera.height = 8;
    const PreparedScene prepared = prepare_scene_releasing_triangles(scene, command.integrator);
    const SceneFeatures& features = prepared.features;
    std::printf("features: %s\n", features.describe().c_str());
    const DeviceScene& arrays = *prepared.device_scene;
    if (arrays.triangles.size() + arrays.spheres.size() + arrays.instances.size() >
        kMaxFixedCountPrimitives)
        std::printf("  (runtime counts: more than %u primitives)\n", kMaxFixedCountPrimitives);

    // The program exactly as a render builds it, through the cache unless it is off.
    WavefrontIntegrator integrator(device, prepared);
    const BuiltProgram& built = integrator.program();
    std::printf("kernels: %s\n",
                command.integrator.general_kernels ? "general (--general)" : "specialised");
    if (const auto& check = integrator.self_check())
        std::printf("self-check: %s (%s%s)\n",
                    check->passed ? "passed" : "FAILED, the general kernels are built instead",
                    check->detail.c_str(), check->from_cache ? ", remembered" : "");
    std::printf("build options: %s\n", built.options.c_str());
    std::printf("sampler: %s\n", to_string(command.integrator.sampler).c_str());
    const ChosenLaunchPlan& plan = integrator.launch_plan();
    std::printf("launch plan: %s (%s)\n", to_string(plan.plan).c_str(), plan.why.c_str());
    std::printf("regeneration: %s (%s); the film folded every %u iterations; %u samples per "
                "pixel a render call\n",
                plan.regeneration ? "on" : "off", plan.regeneration_why.c_str(),
                plan.iterations_per_flush, plan.samples_per_call);
    std::printf("shade order: %s (%s)\n", plan.sorted_shading ? "sorted" : "arrival",
                plan.shade_order_why.c_str());
    if (integrator.tail_rays() > 0)
        std::printf("a wave's tail: its paths traced on in one launch once at most %u rays are "
                    "left, for this pool of %u slots (by default %u, at most a sixteenth of the "
                    "pool; kernels/tail.cl)\n",
                    integrator.tail_rays(), integrator.pool_size(), kDefaultTailRays);
    else
        std::printf("a wave's tail: a launch of each stage per bounce (by default the tail "
                    "kernel runs from a pool of %u slots, with regeneration off and arrival "
                    "order)\n",
                    kTailMinimumPool);
    std::printf("work-groups of %zu work-items; path slots: %s\n", integrator.work_group_size(),
                command.integrator.pool_size == 0
                    ? "one per pixel"
                    : ("at most " + std::to_string(command.integrator.pool_size)).c_str());
    print_geometry_memory(arrays);

    const CachePolicy& cache = command.integrator.program_cache;
    std::printf("program build (the stage and fused kernels are one program):\n");
    std::printf("  compiler start-up (a trivial first build in this process): %s\n",
                format_seconds(warm_up.build_seconds).c_str());
    std::printf("  this run: %s, cache %s%s%s\n", format_seconds(built.build_seconds).c_str(),
                cache_outcome_name(built.cache), built.cache_file.empty() ? "" : ", ",
                built.cache_file.c_str());
    if (!built.cache_note.empty())
        std::printf("  cache note: %s\n", built.cache_note.c_str());

    // Cold: from source with a define no earlier build had, so that no cache
    // (wavepath's or the driver's) can serve it; with argument info, which
    // the empty launches below need.
    const std::string cold_options =
        built.options + " -cl-kernel-arg-info -D WP_INFO_COLD_BUILD=" + std::to_string(entropy());
    BuiltProgram cold = build_wavefront_program(device.context, device.info.device, cold_options,
                                                CachePolicy::off());
    std::printf("  cold (from source, no cache can serve it): %s\n",
                format_seconds(cold.build_seconds).c_str());

    BuiltProgram cached;
    bool have_cached = false;
    if (cache.enabled) {
        cached = build_wavefront_program(device.context, device.info.device, built.options, cache);
        have_cached = cached.cache_hit || cached.cache == CacheOutcome::Driver;
        if (cached.cache == CacheOutcome::Driver)
            std::printf("  cached (from the driver's own kernel cache): %s\n",
                        format_seconds(cached.build_seconds).c_str());
        else if (have_cached)
            std::printf("  cached (loaded from the wavepath cache): %s\n",
                        format_seconds(cached.build_seconds).c_str());
        else
            std::printf("  cached: not available (%s)\n",
                        cached.cache_note.empty() ? "entry not stored" : cached.cache_note.c_str());
    } else {
        std::printf("  cached: the program cache is off (--no-cache or WAVEPATH_NO_CACHE)\n");
    }

    std::vector<std::vector<ArgumentKind>> arguments;
    std::vector<std::string> unknown;
    for (std::string_view name : kStageKernelNames) {
        std::string why;
        arguments.push_back(
            argument_kinds(cl::Kernel(cold.program, std::string(name).c_str()), why));
        unknown.push_back(why);
    }
    std::vector<KernelReport> cold_kernels =
        report_kernels(device, cold.program, arguments, unknown);
    std::vector<KernelReport> cached_kernels =
        report_kernels(device, have_cached ? cached.program : built.program, arguments, unknown);
    std::printf("per kernel (first launch: the driver's deferred compile, if any, for "
                "work-groups of %zu;\n  the second column is the program above, whose "
                "kernels the driver may have cached):\n",
                std::min(kLaunchGroup, device.info.max_work_group_size));
    std::printf("  %-11s %13s %13s %10s %9s %12s %10s\n", "kernel", "launch cold",
                have_cached ? "launch cached" : "launch again", "wg size", "multiple",
                "private mem", "local mem");
    for (std::size_t k = 0; k < cold_kernels.size(); ++k) {
        const KernelReport& c = cold_kernels[k];
        const KernelReport& h = cached_kernels[k];
        auto launch = [](const KernelReport& r) {
            return r.first_launch < 0.0 ? std::string("n/a") : format_seconds(r.first_launch);
        };
        if (h.have_attributes)
            std::printf("  %-11s %13s %13s %10zu %9zu %12s %10s\n", c.name.c_str(),
                        launch(c).c_str(), launch(h).c_str(), h.work_group_size,
                        h.preferred_multiple, format_bytes(h.private_bytes).c_str(),
                        format_bytes(h.local_bytes).c_str());
        else
            std::printf("  %-11s %13s %13s %10s %9s %12s %10s\n", c.name.c_str(), launch(c).c_str(),
                        launch(h).c_str(), "n/a", "n/a", "n/a", "n/a");
        if (!c.why.empty())
            std::printf("    (%s not launched: %s)\n", c.name.c_str(), c.why.c_str());
    }
    return 0;
}

} // namespace wp
