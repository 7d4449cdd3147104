// `wavepath converge`: error against render time (docs/convergence.md).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/render_metadata.hpp"
#include "app/view_cli.hpp"
#include "cl/context.hpp"
#include "cl/device.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/wavefront.hpp"
#include "report/convergence.hpp"
#include "scene/load.hpp"
#include "util/format.hpp"

namespace wp {
CLI::App* add_converge_subcommand(CLI::App& app, ConvergeCommand& command) {
    CLI::App* c = app.add_subcommand(
        "converge", "Render progressively and report the error against render time at 1, 2, "
                    "4, ... samples per pixel (CSV, SVG plot); see docs/convergence.md");
    c->add_option("scene", command.scene, "Scene file (JSON); not needed with --replot");
    add_scene_options(*c);
    c->add_option("--reference,-r", command.reference,
                  "Reference image (.exr or .pfm) of the same size: the true error is measured. "
                  "Without one the error is estimated from the even/odd half images");
    auto* spp = c->add_option("--max-spp", command.max_spp,
                              "Last checkpoint, in samples per pixel (default 256)")
                    ->check(CLI::Range(1u, cli_limits::max_samples_per_pixel));
    auto* time = c->add_option("--max-time", command.max_time,
                               "Render for this many seconds (render time, kernel build "
                               "excluded); the last batch is cut to fit")
                     ->check(positive_finite_number);
    spp->excludes(time);
    c->add_option("--csv", command.csv, "Write the checkpoints as CSV");
    c->add_option("--plot", command.plot, "Write a log-log plot of RMSE against time (SVG)");
    c->add_option("--overlay", command.overlays,
                  "An earlier converge CSV to draw in the same plot (repeatable)");
    c->add_flag("--replot", command.replot,
                "Render nothing: draw --plot from the --overlay CSVs alone");
    c->add_option("--out,-o", command.out, "Write the final image (.exr, .pfm or .png)");
    add_view_options(*c, command.view); // for an --out .png
    c->add_option("--title", command.title, "The plot's title (default: scene, size, device)");
    add_device_option(*c, command.device);
    add_image_size_options(*c, command.width, command.height);
    add_integrator_options(*c, command.integrator);
    return c;
}

int run_converge(const ConvergeCommand& command) {
    check_output(command.csv, {".csv"});
    check_output(command.plot, {".svg"});
    check_output(command.out, kImageExtensions);
    std::vector<NamedPath> inputs = {{"the scene", command.scene},
                                     {"the reference", command.reference}};
    for (const std::string& overlay : command.overlays)
        inputs.push_back({"--overlay", overlay});
    check_distinct_outputs(
        inputs, {{"--csv", command.csv}, {"--plot", command.plot}, {"--out", command.out}});
    // Overlays are read first, so a bad one fails before the render.
    std::vector<ConvergenceRun> runs(1);
    for (const std::string& path : command.overlays)
        runs.push_back(read_convergence_csv(path));
    if (command.replot) {
        if (command.plot.empty() || command.overlays.empty())
            throw std::runtime_error("--replot needs --plot and at least one --overlay");
        runs.erase(runs.begin());
        const std::string title = std::to_string(runs[0].width) + "x" +
                                  std::to_string(runs[0].height) + ", " +
                                  std::to_string(runs.size()) + " runs";
        write_svg(command.plot,
                  convergence_plot(runs, command.title.empty() ? title : command.title));
        return 0;
    }
    if (command.scene.empty())
        throw std::runtime_error("converge needs a scene file (or --replot)");

    Scene scene = load_scene_for_render(command.scene, command.width, command.height);
    check_distinct_outputs(
        scene_inputs(scene),
        {{"--csv", command.csv}, {"--plot", command.plot}, {"--out", command.out}});
    const std::string scene_sha256 = file_sha256(command.scene); // for --out's metadata

    Image reference;
    if (!command.reference.empty())
        reference = read_reference_for(command.reference, scene);

    const IntegratorOptions& options = command.integrator;
    DeviceContext device(select_device(command.device), false);
    WavefrontIntegrator integrator(device, scene, options);

    std::cerr << "wavepath: converge " << scene.camera.width << "x" << scene.camera.height
              << ", estimator " << describe_estimator(options) << ", on " << device.info.name
              << "; kernels built in " << format_text("%.3f", integrator.program().build_seconds)
              << " s (not counted in the times below)\n";

    ConvergenceSettings settings;
    settings.max_spp = command.max_spp;
    settings.max_seconds = command.max_time;
    if (settings.max_spp == 0 && settings.max_seconds <= 0.0)
        settings.max_spp = 256;
    const bool with_reference = !command.reference.empty();
    std::printf("error %s\n%8s %10s %12s %12s %12s %12s\n",
                with_reference ? ("against " + command.reference).c_str()
                               : "estimated from the even/odd half images",
                "spp", "seconds", "RMSE", "relMSE", "efficiency", "rel. eff.");
    std::fflush(stdout);
    Film film(scene.camera.width, scene.camera.height);
    ConvergenceRun& run = runs[0];
    run = run_convergence(
        integrator, film, with_reference ? &reference : nullptr, settings, [](const Checkpoint& c) {
            std::printf("%8u %10.3f %12.5g %12.5g %12.5g %12.5g\n", c.spp, c.seconds, c.rmse,
                        c.rel_mse, c.efficiency, c.rel_efficiency);
            std::fflush(stdout);
        });

    std::cerr << "wavepath: warm-up render (1 spp, first-launch kernel compilation): "
              << format_text("%.3f", run.warm_up_seconds) << " s (not counted)\n";
    if (!command.csv.empty())
        write_convergence_csv(command.csv, run);
    if (!command.plot.empty()) {
        const std::string title = !command.title.empty()
                                      ? command.title
                                      : std::filesystem::path(command.scene).filename().string() +
                                            ", " + std::to_string(run.width) + "x" +
                                            std::to_string(run.height) + ", " + device.info.name;
        write_svg(command.plot, convergence_plot(runs, title));
    }
    if (!command.out.empty() && !run.checkpoints.empty()) {
        Image image = film.mean();
        const Checkpoint& last = run.checkpoints.back();
        image.metadata = render_metadata(
            {.scene_file = command.scene,
             .scene_sha256 = scene_sha256,
             .width = run.width,
             .height = run.height,
             .samples_done = last.spp,
             .samples_requested = settings.max_spp > 0 ? settings.max_spp : last.spp,
             .options = options,
             .devices = {device.info.name},
             .launch_plan = integrator.launch_summary(),
             .render_seconds = last.seconds});
        write_result_image(command.out, image, view_for_scene(command.view, scene));
    }
    const RenderStats& stats = integrator.stats();
    if (stats.nonfinite_samples > 0 || stats.capped_paths > 0)
        std::cerr << "wavepath: warning: " << stats.nonfinite_samples
                  << " NaN/Inf samples dropped, " << stats.capped_paths
                  << " paths cut by the depth cap\n";
    return 0;
}

} // namespace wp
