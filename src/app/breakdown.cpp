// `wavepath breakdown`: each path type's share of a render's mean squared
// error, at a few sample counts, near the light and elsewhere.
//
// It renders the scene 1 + 2 x 5 times with one seed: the full estimate, and
// for each path type the part alone and the rest without it (report/
// error_breakdown.hpp says why three), each progressively through the
// requested sample counts. A part whose render is black everywhere is zero
// and needs no rest.
#include "app/breakdown.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "cl/context.hpp"
#include "cl/device.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "render/film.hpp"
#include "render/wavefront.hpp"
#include "report/error_breakdown.hpp"

namespace wp {
namespace {

// One render's estimate and the variance of its mean, at one sample count.
struct Snapshot {
    Image mean;
    Image variance;
    double seconds = 0.0; // render time up to here
};

std::vector<Snapshot> render_checkpoints(DeviceContext& device, const Scene& scene,
                                         IntegratorOptions options, std::uint32_t path_types,
                                         const std::vector<std::uint32_t>& spp) {
    options.path_types = path_types;
    std::cerr << "wavepath: breakdown: rendering path types " << describe_path_types(path_types)
              << "\n";
    WavefrontIntegrator integrator(device, scene, options);
    Film film(scene.camera.width, scene.camera.height);
    std::vector<Snapshot> snapshots;
    std::uint32_t done = 0;
    for (std::uint32_t n : spp) {
        integrator.render(done, n - done, film);
        done = n;
        snapshots.push_back(
            {film.mean(), film.variance_of_mean(), integrator.stats().render_seconds});
    }
    if (integrator.stats().nonfinite_samples > 0)
        std::cerr << "wavepath: warning: " << integrator.stats().nonfinite_samples
                  << " NaN/Inf samples dropped (path types " << describe_path_types(path_types)
                  << ")\n";
    return snapshots;
}

bool black(const Snapshot& s) {
    return std::all_of(s.mean.rgb.begin(), s.mean.rgb.end(), [](float v) { return v == 0.0f; }) &&
           std::all_of(s.variance.rgb.begin(), s.variance.rgb.end(),
                       [](float v) { return v == 0.0f; });
}

double percent(double part, double whole) {
    return whole != 0.0 ? 100.0 * part / whole : 0.0;
}

} // namespace

CLI::App* add_breakdown_subcommand(CLI::App& app, BreakdownCommand& command) {
    CLI::App* c = app.add_subcommand(
        "breakdown", "Each path type's share of the mean squared error (variance / n from the "
                     "film, no reference needed), near the light and elsewhere; see "
                     "docs/convergence.md");
    c->add_option("scene", command.scene, "Scene file (JSON)")->required();
    add_scene_options(*c);
    c->add_option("--reference,-r", command.reference,
                  "A high-sample reference (.exr or .pfm) of the same size: the full "
                  "estimate's MSE against it too, and the near-light pixels taken from it");
    c->add_option("--spp", command.spp,
                  "Sample counts to report, ascending, of one progressive render (default 64 256)")
        ->delimiter(',')
        ->check(CLI::Range(2u, cli_limits::max_samples_per_pixel));
    c->add_option("--light-threshold", command.light_threshold,
                  "A pixel whose brightest channel is above this sees the light (directly or in "
                  "a mirror); in the reference, else in the full render's last estimate")
        ->capture_default_str()
        ->check(positive_finite_number);
    c->add_option("--light-radius", command.light_radius,
                  "Pixels around those that count as near the light")
        ->capture_default_str()
        ->check(CLI::Range(0, 64));
    c->add_flag("--total-only", command.total_only,
                "Render only the full estimate: its MSE near the light and elsewhere, and time");
    add_device_option(*c, command.device);
    add_image_size_options(*c, command.width, command.height);
    add_integrator_options(*c, command.integrator);
    return c;
}

int run_breakdown(const BreakdownCommand& command) {
    if (command.integrator.path_types != kAllPathTypes)
        throw std::runtime_error("breakdown renders every path type itself; drop --path-types");
    std::vector<std::uint32_t> spp = command.spp;
    if (spp.empty() || !std::is_sorted(spp.begin(), spp.end()) ||
        std::adjacent_find(spp.begin(), spp.end()) != spp.end())
        throw std::runtime_error("--spp needs sample counts in ascending order, each once");

    const Scene scene = load_scene_for_render(command.scene, command.width, command.height);
    Image reference;
    if (!command.reference.empty())
        reference = read_reference_for(command.reference, scene);

    DeviceContext device(select_device(command.device), false);
    const IntegratorOptions& options = command.integrator;
    const std::vector<Snapshot> whole =
        render_checkpoints(device, scene, options, kAllPathTypes, spp);
    const std::vector<bool> near =
        bright_region(reference.rgb.empty() ? whole.back().mean : reference,
                      command.light_threshold, command.light_radius);

    // parts[t][i]: the share of path type t at checkpoint i (empty: no light of that type).
    std::vector<std::vector<Image>> shares(WP_PATH_TYPE_COUNT);
    std::vector<std::vector<double>> light(WP_PATH_TYPE_COUNT);
    for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT && !command.total_only; ++type) {
        const std::uint32_t alone = 1u << type;
        const std::vector<Snapshot> part = render_checkpoints(device, scene, options, alone, spp);
        for (const Snapshot& s : part)
            light[type].push_back(region_means(s.mean, near).total);
        if (black(part.back()))
            continue;
        const std::vector<Snapshot> rest =
            render_checkpoints(device, scene, options, kAllPathTypes & ~alone, spp);
        for (std::size_t i = 0; i < spp.size(); ++i)
            shares[type].push_back(
                variance_share(whole[i].variance, part[i].variance, rest[i].variance));
    }

    std::printf("# %s, %dx%d, seed %u, estimator %s\n\n", command.scene.c_str(), scene.camera.width,
                scene.camera.height, options.seed, describe_estimator(options).c_str());
    std::printf("Near the light: %.2f %% of the pixels (brightest channel above %g in the %s, "
                "%d px around).\nMSE = variance of the mean, from the film (no reference); a "
                "part's share is its covariance with the whole.\n",
                100.0 * region_fraction(near), command.light_threshold,
                reference.rgb.empty() ? "render" : "reference", command.light_radius);
    for (std::size_t i = 0; i < spp.size(); ++i) {
        const RegionMeans total = region_means(whole[i].variance, near);
        const double mean = region_means(whole[i].mean, near).total;
        std::printf("\n## %u spp (%.2f s)\n\n| part | light | MSE share | %% | near the light "
                    "| elsewhere |\n| --- | --- | --- | --- | --- | --- |\n",
                    spp[i], whole[i].seconds);
        for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT && !command.total_only; ++type) {
            const RegionMeans share =
                shares[type].empty() ? RegionMeans{} : region_means(shares[type][i], near);
            std::printf("| %s | %.1f %% | %.4g | %.1f %% | %.4g | %.4g |\n",
                        path_type_name(type).c_str(), percent(light[type][i], mean), share.total,
                        percent(share.total, total.total), share.inside, share.outside);
        }
        std::printf("| total | 100 %% | %.4g | 100 %% | %.4g | %.4g |\n", total.total, total.inside,
                    total.outside);
        if (!reference.rgb.empty()) {
            const RegionMeans error = region_squared_error(whole[i].mean, reference, near);
            std::printf("| against the reference | | %.4g | %.0f %% | %.4g | %.4g |\n", error.total,
                        percent(error.total, total.total), error.inside, error.outside);
        }
    }
    std::fflush(stdout);
    return 0;
}

} // namespace wp
