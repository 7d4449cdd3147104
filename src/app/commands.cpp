#include "app/commands.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "app/cli_options.hpp"
#include "app/interrupt.hpp"
#include "app/render_devices.hpp"
#include "app/render_loop.hpp"
#include "app/render_metadata.hpp"
#include "app/view_cli.hpp"
#include "cl/context.hpp"
#include "cl/device.hpp"
#include "image/exr.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/checkpoint.hpp"
#include "render/multi_device.hpp"
#include "render/self_check.hpp"
#include "render/wavefront.hpp"
#include "report/device_profile.hpp"
#include "report/profile_report.hpp"
#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "util/file.hpp"

namespace wp {

void check_output(const std::string& path, const std::vector<std::string>& extensions) {
    if (path.empty())
        return;
    check_writable(path);
    const std::string extension = lower_extension(path);
    if (extensions.empty() ||
        std::find(extensions.begin(), extensions.end(), extension) != extensions.end())
        return;
    std::string list;
    for (const std::string& e : extensions)
        list += (list.empty() ? "" : e == extensions.back() ? " or " : ", ") + e;
    throw FileError("cannot write '" + path + "'",
                    "unsupported extension '" + std::filesystem::path(path).extension().string() +
                        "' (use " + list + ")");
}

void check_distinct_outputs(const std::vector<NamedPath>& inputs,
                            const std::vector<NamedPath>& outputs) {
    std::vector<std::pair<std::filesystem::path, const NamedPath*>> seen;
    for (const NamedPath& input : inputs)
        if (!input.path.empty())
            seen.emplace_back(resolved_path(input.path), &input);
    for (const NamedPath& output : outputs) {
        std::error_code ec;
        // A device (/dev/null) is written through, not replaced: several
        // outputs may share it.
        if (output.path.empty() || std::filesystem::is_character_file(output.path, ec))
            continue;
        const std::filesystem::path resolved = resolved_path(output.path);
        for (const auto& [other, named] : seen)
            if (other == resolved)
                throw FileError("cannot write " + output.role + " '" + output.path + "'",
                                "it is the same file as " + named->role + " '" + named->path + "'");
        seen.emplace_back(resolved, &output);
    }
}

std::vector<NamedPath> scene_inputs(const Scene& scene) {
    std::vector<NamedPath> inputs = {{"the scene", scene.source}};
    for (const std::string& file : scene.files)
        inputs.push_back({"input file", file}); // a mesh, a texture, an environment map
    return inputs;
}

void write_result_image(const std::string& path, const Image& image, const ViewOptions& view,
                        std::span<const ExrLayer> layers) {
    const auto write = [&](const std::filesystem::path& to) {
        if (layers.empty())
            write_image(to, image, view);
        else
            write_exr(to, image, layers);
    };
    try {
        write(path);
        return;
    } catch (const FileError& e) {
        // Same extension, so the fallback holds the same format.
        const std::filesystem::path fallback = std::filesystem::temp_directory_path() /
                                               ("wavepath-" + std::to_string(::getpid()) + "-" +
                                                std::filesystem::path(path).filename().string());
        try {
            write(fallback);
        } catch (const std::exception&) {
            throw e; // nowhere to save it: the first failure is the one to report
        }
        throw FileError(e.what(), "the image was saved to '" + fallback.string() + "' instead");
    }
}

namespace {

// Refuses an --aov list that parse_aovs does not take.
const CLI::Validator aov_list(
    [](const std::string& text) -> std::string {
        try {
            parse_aovs(text);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return {};
    },
    "AOVS");

// The EXR layers of the AOVs asked for (docs/lights-and-camera.md, "AOVs"):
// albedo.R/G/B, normal.X/Y/Z and depth.Z, Blender's and OpenEXR's names.
std::vector<ExrLayer> aov_layers(const Film& film, std::uint32_t aovs) {
    static const std::vector<std::string> channels[kAovCount] = {
        {"R", "G", "B"}, {"X", "Y", "Z"}, {"Z"}};
    std::vector<ExrLayer> layers;
    for (std::uint32_t number = 0; number < kAovCount; ++number)
        if (aovs & (1u << number))
            layers.push_back({aov_name(number), channels[number], film.aov_mean(number)});
    return layers;
}

} // namespace

CLI::App* add_render_subcommand(CLI::App& app, RenderCommand& command) {
    CLI::App* r = app.add_subcommand("render", "Render a scene to an image");
    r->add_option("scene", command.scene, "Scene file (JSON, see docs/scene-format.md)")
        ->required();
    add_scene_options(*r);
    r->add_option("--out,-o", command.out,
                  "Output image; its extension picks the format: .exr or .pfm (linear HDR), "
                  ".png (view)")
        ->capture_default_str();
    r->add_option("--png", command.png, "Also write a PNG view of the image (a .png name)");
    r->add_option("--spp,-s", command.spp, "Samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1u, cli_limits::max_samples_per_pixel));
    add_device_list_option(*r, command.device);
    add_image_size_options(*r, command.width, command.height);
    add_integrator_options(*r, command.integrator);
    add_view_options(*r, command.view);
    r->add_flag(
        "--profile", command.profile,
        "Print per-stage device times, items and rates at the end (OpenCL event profiling)");
    r->add_option(
        "--profile-json", command.profile_json,
        "Write the profile as JSON, with device, scene, resolution, spp and build options");
    r->add_option("--variance", command.variance,
                  "Also write each pixel's variance of the mean (sample variance / samples; "
                  ".exr or .pfm), for `wavepath compare --variance`");
    r->add_option_function<std::string>(
         "--aov",
         [&command](const std::string& list) { command.integrator.aovs = parse_aovs(list); },
         "Also write these AOVs of the camera ray's first hit, per pixel the mean over its "
         "samples, as layers of the .exr --out: a comma-separated list of albedo (albedo.R/G/B), "
         "normal (the shading normal facing the camera, normal.X/Y/Z), depth (the distance "
         "along the ray, depth.Z); 0 where the ray misses (docs/lights-and-camera.md, \"AOVs\")")
        ->check(aov_list);
    r->add_option("--trace", command.trace,
                  "Write every kernel launch and transfer as a Chrome trace (Perfetto, "
                  "chrome://tracing)");
    add_render_loop_options(*r, command.loop, command.spp);
    add_checkpoint_options(*r, command.checkpoints);
    return r;
}

Scene load_scene_for_render(const std::string& path, int width, int height) {
    Scene scene = load_scene(path, scene_read_options());
    for (const std::string& warning : scene.warnings)
        std::cerr << "wavepath: warning: " << warning << "\n";
    if (!has_emitter(scene))
        std::cerr << "wavepath: warning: " << path
                  << ": no shape emits light (no triangle has an emitter material or one with "
                     "emission, and no emitter is lit), so the image will be black\n";
    if (width > 0)
        scene.camera.width = width;
    if (height > 0)
        scene.camera.height = height;
    return scene;
}

Image read_reference_for(const std::string& path, const Scene& scene) {
    Image reference = read_image(path);
    if (reference.width != scene.camera.width || reference.height != scene.camera.height)
        throw std::runtime_error("reference '" + path + "' is " + std::to_string(reference.width) +
                                 "x" + std::to_string(reference.height) + " but the render is " +
                                 std::to_string(scene.camera.width) + "x" +
                                 std::to_string(scene.camera.height) + " (use --width/--height)");
    if (const std::size_t bad = count_nonfinite(reference); bad > 0)
        throw std::runtime_error("reference '" + path + "' has " + std::to_string(bad) +
                                 " NaN or infinite values; errors against it would be "
                                 "meaningless");
    return reference;
}

int run_devices(bool check) {
    std::vector<DeviceInfo> devices = list_devices();
    if (devices.empty()) {
        std::cerr << "wavepath: no OpenCL device found (is an ICD such as pocl-opencl-icd "
                     "installed?)\n";
        return 1;
    }
    std::cout << describe_devices(devices);
    if (!check)
        return 0;
    std::cout << "self-check (specialised against general kernels, a built-in scene with every "
                 "feature):\n";
    std::cout.flush();
    int status = 0;
    const Scene scene = self_check_scene();
    IntegratorOptions options;
    options.self_check = true;
    for (const DeviceInfo& info : devices) {
        std::string verdict;
        try {
            DeviceContext device(info);
            const SelfCheckVerdict v = check_kernels(device, scene, options);
            verdict = std::string(v.passed ? "pass" : "FAIL") + " (" + v.detail +
                      (v.from_cache ? ", remembered" : "") + ")";
            status |= v.passed ? 0 : 1;
        } catch (const std::exception& e) {
            verdict = std::string("FAIL (") + e.what() + ")";
            status = 1;
        }
        std::cout << "  " << info.index_string() << "  " << info.name << ", driver "
                  << info.driver_version << ": " << verdict << "\n";
    }
    return status;
}

Film allocate_film(int width, int height) {
    try {
        return Film(width, height);
    } catch (const std::bad_alloc&) {
        // Per pixel (film.hpp): rgb sums, sums of squares and odd-sample sums
        // in double, and two 64-bit counts.
        const double bytes = static_cast<double>(width) * static_cast<double>(height) *
                             (9 * sizeof(double) + 2 * sizeof(std::uint64_t));
        char size[32];
        std::snprintf(size, sizeof size, "%.0f MiB", bytes / (1 << 20));
        throw std::runtime_error("out of host memory: the film of " + std::to_string(width) + "x" +
                                 std::to_string(height) + " pixels needs " + size +
                                 " (try a smaller --width/--height)");
    }
}

int run_render(const RenderCommand& command) {
    if (const std::optional<int> status = run_render_as_mpi_worker(command))
        return *status; // a rank other than 0 of an MPI job (render_devices.hpp)
    check_output(command.out, kImageExtensions);
    // --png is the view: an .exr or .pfm there would silently be linear.
    check_output(command.png, {".png"});
    check_output(command.profile_json);
    check_output(command.trace);
    check_output(command.variance, {".exr", ".pfm"});
    check_output(command.checkpoints.file);
    // --checkpoint may be the --resume file (go on saving where it started).
    const std::vector<NamedPath> outputs = {{"--out", command.out},
                                            {"--png", command.png},
                                            {"--profile-json", command.profile_json},
                                            {"--trace", command.trace},
                                            {"--variance", command.variance},
                                            {"--checkpoint", command.checkpoints.file}};
    check_distinct_outputs({{"the scene", command.scene}}, outputs);
    check_distinct_outputs({{"--resume", command.checkpoints.resume}},
                           {{"--out", command.out},
                            {"--png", command.png},
                            {"--profile-json", command.profile_json},
                            {"--trace", command.trace}});

    if (command.integrator.aovs != 0) {
        if (lower_extension(command.out) != ".exr")
            throw std::runtime_error("--aov: the AOVs are layers of an EXR, and --out '" +
                                     command.out + "' is not an .exr");
    }
    Scene scene = load_scene_for_render(command.scene, command.width, command.height);
    check_distinct_outputs(scene_inputs(scene), outputs); // its meshes, known once it is read
    const std::string scene_sha256 = file_sha256(command.scene); // for the metadata
    const ViewOptions view = view_for_scene(command.view, scene);
    RenderLoop loop(command.loop, view); // a preview port in use fails here

    const bool profiling =
        command.profile || !command.profile_json.empty() || !command.trace.empty();
    // The checkpoints' scene hash covers the triangles, which open_renderer
    // frees; hashed only for checkpoints (a 10^6-triangle mesh's 208 MB took
    // a tenth of its render's loading time).
    const bool checkpointing =
        !command.checkpoints.file.empty() || !command.checkpoints.resume.empty();
    const std::uint64_t scene_hash = checkpointing ? scene_content_hash(scene) : 0;
    // Every device of --device, and with MPI the other ranks' (render_devices.hpp).
    std::unique_ptr<MultiDeviceRenderer> renderer = open_renderer(command, scene, profiling);
    MultiDeviceRenderer& integrator = *renderer;
    // The command line's options with the scene's own (a Mitsuba file's
    // max_depth, rr_depth, hide_emitters: prepared_scene.hpp), as rendered:
    // what the metadata and the checkpoints record.
    const IntegratorOptions& options = integrator.integrator().options();
    // After the integrator, whose device check is arithmetic: allocating (and
    // zeroing) a film first would take a minute and all host memory before
    // an image too big for the device is refused.
    Film film = allocate_film(scene.camera.width, scene.camera.height);
    RenderCheckpoints checkpoints(
        command.checkpoints,
        checkpoint_identity(scene_hash, scene, options, integrator.integrator().program().options));
    const std::uint32_t resumed = checkpoints.resume(film, command.spp); // 0 without --resume

    std::cerr << "wavepath: " << scene.camera.width << "x" << scene.camera.height << " "
              << describe_halt_conditions(command.loop, command.spp) << " on "
              << integrator.describe() << " (kernels built in "
              << integrator.integrator().program().build_seconds
              << " s; features: " << integrator.integrator().features().describe() << ")\n";

    const std::uint64_t pixels = static_cast<std::uint64_t>(scene.camera.width) *
                                 static_cast<std::uint64_t>(scene.camera.height);
    // Samples are rendered a few per call, so that Ctrl-C (interrupt.hpp),
    // the halt conditions and the checkpoints are dealt with between calls,
    // where every pixel has the same number. Always the same split for the
    // same options, so the image is too.
    begin_interruptible_work(); // until now a signal ends the process at once
    const RenderLoopResult rendered = loop.run(
        film, command.spp,
        integrator.samples_per_call(integrator.integrator().launch_plan().samples_per_call),
        [&](std::uint32_t first, std::uint32_t count, const std::function<void(double)>& progress) {
            integrator.render(first, count, film, progress);
            checkpoints.save_if_due(first + count, film);
        },
        resumed);
    const std::uint32_t spp = rendered.spp;
    const bool interrupted = rendered.interrupted();

    integrator.finish(); // the MPI ranks' shares arrive
    Image image = film.mean();
    image.metadata = render_metadata({.scene_file = command.scene,
                                      .scene_sha256 = scene_sha256,
                                      .width = scene.camera.width,
                                      .height = scene.camera.height,
                                      .samples_done = spp,
                                      .samples_requested = command.spp,
                                      .samples_resumed = resumed,
                                      .options = options,
                                      .devices = device_names(integrator),
                                      .launch_plan = integrator.integrator().launch_summary(),
                                      .render_seconds = integrator.stats().render_seconds});
    write_result_image(command.out, image, view, aov_layers(film, options.aovs));
    if (!command.png.empty())
        write_result_image(command.png, image, view);
    if (!command.variance.empty()) {
        Image variance = film.variance_of_mean();
        variance.metadata = image.metadata;
        write_result_image(command.variance, variance, view);
    }
    checkpoints.save(spp, film);

    const RenderStats stats = integrator.stats();
    double seconds = stats.render_seconds;
    double samples = static_cast<double>(pixels) * (spp - resumed); // this run's
    double rays = static_cast<double>(stats.camera_rays + stats.bounce_rays + stats.shadow_rays);
    std::printf("rendered %s: %dx%d, %u spp, %.2f s, %.3g samples/s, %.3g Mrays/s "
                "(%.0f camera, %.0f bounce, %.0f shadow rays)\n",
                command.out.c_str(), scene.camera.width, scene.camera.height, spp, seconds,
                samples / seconds, rays / seconds / 1e6, static_cast<double>(stats.camera_rays),
                static_cast<double>(stats.bounce_rays), static_cast<double>(stats.shadow_rays));
    std::printf("paths cut by the depth cap (%u): %llu; NaN/Inf samples dropped: %llu\n",
                options.max_depth, static_cast<unsigned long long>(stats.capped_paths),
                static_cast<unsigned long long>(stats.nonfinite_samples));
    if (profiling) {
        ProfileContext context;
        context.device = integrator.describe();
        context.scene = command.scene;
        context.width = scene.camera.width;
        context.height = scene.camera.height;
        context.spp = spp;
        context.build_options = integrator.integrator().program().options;
        context.build_seconds = integrator.integrator().program().build_seconds;
        context.regeneration = integrator.integrator().launch_plan().regeneration;
        context.pool_size = integrator.integrator().pool_size();
        context.launch_plan = to_string(integrator.integrator().launch_plan().plan);
        if (command.profile)
            std::printf("\n%s", multi_device_profile_table(integrator, context).c_str());
        if (!command.profile_json.empty())
            write_multi_device_profile_json(command.profile_json, integrator, context);
        if (!command.trace.empty())
            write_multi_device_trace(command.trace, integrator);
    } else {
        print_device_shares(integrator); // with several devices
    }
    if (interrupted) {
        std::fflush(stdout);
        std::cerr << "wavepath: interrupted: the outputs hold " << spp << " of the " << command.spp
                  << " samples per pixel asked for\n";
        return 128 + interrupt_signal(); // the shell's code for "ended by this signal"
    }
    if (interrupt_requested()) {
        // A signal after the last wave, while the outputs were written: they
        // are complete, but whoever sent it must still see that it arrived.
        std::fflush(stdout);
        std::cerr << "wavepath: interrupted after the render: the outputs hold all " << spp
                  << " samples per pixel\n";
        return 128 + interrupt_signal();
    }
    return 0;
}

} // namespace wp
