// wavepath: a wavefront Monte Carlo path tracer on OpenCL.
//
// This file only parses the command line and turns every failure into one
// line on stderr and a non-zero exit; the subcommands live in commands.cpp.
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "cl/device.hpp"
#include "cl/error.hpp"
#include "cl/program.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"

int main(int argc, char** argv) {
    CLI::App app{"wavepath: a wavefront Monte Carlo path tracer on OpenCL"};
    app.require_subcommand(1);

    app.add_subcommand("devices", "List every OpenCL platform and device");

    wp::RenderCommand render;
    std::string tonemap = "srgb";
    CLI::App* r = app.add_subcommand("render", "Render a scene to an image");
    r->add_option("scene", render.scene, "Scene file (JSON, see docs/scene-format.md)")->required();
    r->add_option("--out,-o", render.out,
                  "Output image; its extension picks the format: .exr or .pfm (linear HDR), "
                  ".png (view)")
        ->capture_default_str();
    r->add_option("--png", render.png, "Also write a PNG view of the image");
    r->add_option("--spp,-s", render.spp, "Samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 24));
    r->add_option("--device,-d", render.device,
                  "OpenCL device: an index P:D from `wavepath devices`, or part of its name "
                  "(default: first GPU, else first CPU)");
    r->add_option("--seed", render.seed, "Random seed; the same seed gives the same image")
        ->capture_default_str();
    r->add_option("--width", render.width, "Image width (default: the scene's)")
        ->check(CLI::Range(1, 16384));
    r->add_option("--height", render.height, "Image height (default: the scene's)")
        ->check(CLI::Range(1, 16384));
    r->add_option("--max-depth", render.max_depth,
                  "Safety cap on bounces; Russian roulette ends paths long before it. Paths it "
                  "cuts are counted and reported")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 20));
    r->add_option("--tonemap", tonemap,
                  "PNG view: 'srgb' (exposure, then the sRGB curve) or 'seed' (the report's: "
                  "sqrt, divided by the image maximum, times 255.99)")
        ->capture_default_str()
        ->check(CLI::IsMember({"srgb", "seed"}));
    r->add_option("--exposure", render.view.exposure_stops, "PNG exposure in stops (srgb view)")
        ->capture_default_str();
    r->add_flag("--general", render.general,
                "Build the all-features kernels instead of the scene's specialised ones");
    r->add_flag("--regeneration,!--no-regeneration", render.regeneration,
                "Refill the slots of finished paths with new samples at once, keeping queues full "
                "(default: off, one wave of samples at a time; see docs/profiling.md)");
    r->add_option("--pool", render.pool,
                  "Path slots on the device (default: one per pixel); fewer use less memory");
    r->add_flag(
        "--profile", render.profile,
        "Print per-stage device times, items and rates at the end (OpenCL event profiling)");
    r->add_option(
        "--profile-json", render.profile_json,
        "Write the profile as JSON, with device, scene, resolution, spp and build options");
    r->add_option("--trace", render.trace,
                  "Write every kernel launch and transfer as a Chrome trace (Perfetto, "
                  "chrome://tracing)");

    wp::BenchCommand bench;
    CLI::App* b = app.add_subcommand(
        "bench", "Print throughput figures for fixed workloads: a render of the scene with and "
                 "without path regeneration, and each tracing stage alone on 2^20 random rays");
    b->add_option("scene", bench.scene, "Scene file")->capture_default_str();
    b->add_option("--device,-d", bench.device, "OpenCL device (as for render)");
    b->add_option("--size", bench.size, "Rendered workload: size x size pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    b->add_option("--spp", bench.spp, "Rendered workload: samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1u, 4096u));
    b->add_option("--repetitions", bench.repetitions, "Launches per stage-alone workload")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));

    // Convergence reports (converge.cpp, compare.cpp; docs/convergence.md).
    wp::ConvergeCommand converge;
    wp::CompareCommand compare;
    CLI::App* converge_app = wp::add_converge_subcommand(app, converge);
    CLI::App* compare_app = wp::add_compare_subcommand(app, compare);
    wp::InfoCommand info;
    CLI::App* info_app = wp::add_info_subcommand(app, info);
    wp::add_no_cache_flag(r);

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) { // --help
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "wavepath: error: " << e.what() << " (see wavepath --help)\n";
        return 2;
    }
    render.view.tonemap = tonemap == "seed" ? wp::ToneMap::Seed : wp::ToneMap::Srgb;

    try {
        if (app.got_subcommand("devices"))
            return wp::run_devices();
        if (app.got_subcommand("bench"))
            return wp::run_bench(bench);
        if (converge_app->parsed())
            return wp::run_converge(converge);
        if (compare_app->parsed())
            return wp::run_compare(compare);
        if (info_app->parsed())
            return wp::run_info(info);
        return wp::run_render(render);
    } catch (const wp::BuildError& e) {
        std::cerr << e.log() << "\nwavepath: error: " << e.what() << "\n";
    } catch (const cl::Error& e) {
        std::cerr << "wavepath: error: " << wp::describe_cl_error(e) << "\n";
    } catch (const std::exception& e) {
        std::cerr << "wavepath: error: " << e.what() << "\n";
    }
    return 1;
}
