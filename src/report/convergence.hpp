// Error against render time: a progressive render with checkpoints.
//
// run_convergence renders samples [0, 1), [1, 2), [2, 4), [4, 8), ... into one
// film (counter-based random numbers make that the same image as rendering
// [0, n) at once) and measures the error at every checkpoint: against a
// reference image when there is one, otherwise estimated from the film's two
// half images (even and odd sample indices; see mse_from_halves). Times are
// the integrator's render time only: the kernel build and the metrics are not
// counted. See docs/convergence.md.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/film.hpp"
#include "render/wavefront.hpp"
#include "report/svg_plot.hpp"

namespace wp {

struct ConvergenceSettings {
    std::uint32_t max_spp = 256; // 0: no sample limit (then max_seconds must be > 0)
    double max_seconds = 0.0;    // 0: no time limit; else the last batch is cut to fit
    // Render one sample per pixel into a scratch film first, untimed: PoCL
    // compiles each kernel's work-group function at its first launch (0.2 to
    // 0.8 s here), which belongs with the kernel build, not with the 1 spp
    // checkpoint.
    bool warm_up = true;
    // Render samples [first_sample, first_sample + spp): runs at different
    // first samples are independent (counter-based random numbers).
    std::uint32_t first_sample = 0;
};

struct Checkpoint {
    std::uint32_t spp = 0;
    double seconds = 0.0; // render time of samples [0, spp)
    bool against_reference = false;
    // The error used for the report: true error against the reference, or the
    // half-image estimate without one (NaN at 1 spp, which has no odd half).
    double mse = 0.0;
    double rmse = 0.0;
    double rel_mse = 0.0;
    double efficiency = 0.0;     // 1 / (mse x seconds)
    double rel_efficiency = 0.0; // 1 / (rel_mse x seconds)
    // The half-image estimates, always (NaN at 1 spp).
    double mse_halves = 0.0;
    double rel_mse_halves = 0.0;
};

// The metrics of `film` (samples [first_sample, first_sample + spp) of every
// pixel) after `seconds`. `reference` may be null; otherwise it must have the
// film's size.
Checkpoint measure_checkpoint(const Film& film, std::uint32_t spp, double seconds,
                              const Image* reference, std::uint32_t first_sample = 0);

// The spp of the checkpoints up to max_spp: 1, 2, 4, ..., and max_spp itself.
std::vector<std::uint32_t> checkpoint_schedule(std::uint32_t max_spp);

// One run, as written to and read from a CSV file.
struct ConvergenceRun {
    std::string estimator; // describe_estimator
    int width = 0;
    int height = 0;
    double build_seconds = 0.0;   // kernel build, not in any checkpoint's seconds
    double warm_up_seconds = 0.0; // the warm-up render: not counted either
    std::vector<Checkpoint> checkpoints;
};

// Renders progressively into `film` (empty, the integrator's size) and returns
// the run (estimator, size, build and warm-up times, checkpoints);
// `on_checkpoint` sees each checkpoint as it is measured.
ConvergenceRun run_convergence(WavefrontIntegrator& integrator, Film& film, const Image* reference,
                               const ConvergenceSettings& settings,
                               const std::function<void(const Checkpoint&)>& on_checkpoint = {});

// CSV with a header line and one line per checkpoint; columns: estimator, width,
// height, spp, seconds, build_seconds, warm_up_seconds, error_source (reference or
// halves), mse, rmse, rel_mse, efficiency, rel_efficiency, mse_halves,
// rel_mse_halves. Unknown values are "nan".
std::string convergence_csv(const ConvergenceRun& run);
void write_convergence_csv(const std::filesystem::path& path, const ConvergenceRun& run);
// Reads what write_convergence_csv wrote; throws std::runtime_error naming the file
// and line on anything else.
ConvergenceRun read_convergence_csv(const std::filesystem::path& path);

// RMSE against render time, one series per run (spp beside the first run's
// points), and the ideal slope -1/2 through the last point of the first run.
LogLogPlot convergence_plot(const std::vector<ConvergenceRun>& runs, const std::string& title);

// Least-squares slope of log(y) against log(x) over the points with x in [x_min,
// x_max] (positive, finite values only); NaN with fewer than two.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double x_min = 0.0,
                     double x_max = HUGE_VAL);

// The time at which the error first reaches `target` (relMSE), interpolated in
// log-log between the checkpoints around it; NaN if it never does.
double time_to_rel_mse(const std::vector<Checkpoint>& checkpoints, double target);

} // namespace wp
