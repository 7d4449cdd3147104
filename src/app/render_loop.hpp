// The progressive loop of `wavepath render`: samples are rendered a few per
// call, and between calls, where every pixel has the same number of
// samples, the loop checks the halt conditions (--spp, --time,
// --target-error) and Ctrl-C (interrupt.hpp), reports progress
// (progress.hpp) and publishes the live preview (preview_server.hpp).
//
// The first halt condition met ends the render:
//   --spp N           N samples per pixel are done;
//   --time SECONDS    the next call would end past the budget (its time is
//                     estimated from the calls before it), counted from the
//                     loop's start (the kernel build and scene load excluded);
//   --target-error X  the relMSE estimated from the even and odd half images
//                     (image/metrics.hpp rel_mse_from_halves) is below X.
// With --time or --target-error and no --spp, the spp bound is the CLI's
// largest (cli_limits::max_samples_per_pixel). At least one call is made.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "image/tonemap.hpp"
#include "render/film.hpp"

namespace CLI {
class App;
}

namespace wp {

struct RenderLoopOptions {
    double time_budget = 0.0;  // seconds; 0: none
    double target_error = 0.0; // relMSE; 0: none
    bool spp_given = false;    // --spp was on the command line
    bool quiet = false;        // no progress report
    int preview_port = -1;     // -1: no preview; 0: a free port
    std::string preview_bind = "127.0.0.1";
};

inline constexpr int kDefaultPreviewPort = 8642;

// --time, --target-error, --quiet, --preview [PORT] and --preview-bind on
// `render`; after parsing, `spp` becomes the CLI's largest when --time or
// --target-error is given without --spp.
void add_render_loop_options(CLI::App& render, RenderLoopOptions& options, std::uint32_t& spp);

// The halt conditions in words, for the line that starts the render:
// "64 spp", "a time budget of 3 s", "64 spp or a time budget of 3 s, whichever first".
std::string describe_halt_conditions(const RenderLoopOptions& options, std::uint32_t spp);

enum class HaltReason { SampleCount, TimeBudget, TargetError, Interrupted };

// relMSE estimated from the half images at `spp` samples per pixel.
struct ErrorEstimate {
    std::uint32_t spp = 0; // 0: no estimate
    double rel_mse = 0.0;
};

struct RenderLoopResult {
    std::uint32_t spp = 0; // samples per pixel in the film
    HaltReason reason = HaltReason::SampleCount;
    double seconds = 0.0;   // wall time of the loop
    ErrorEstimate estimate; // the last one made, if any
    ErrorEstimate previous; // the one before it
    bool interrupted() const { return reason == HaltReason::Interrupted; }
};

// Renders samples [first_sample, first_sample + count) of every pixel into
// the film the loop was given, calling on_progress(samples per pixel done in
// this call) as they finish (WavefrontIntegrator::render's contract).
using RenderCall = std::function<void(std::uint32_t first_sample, std::uint32_t count,
                                      const std::function<void(double)>& on_progress)>;

class PreviewServer;

class RenderLoop {
  public:
    // Starts the preview server when options ask for one, so that a port in
    // use fails before any work (std::runtime_error), and prints its address.
    RenderLoop(const RenderLoopOptions& options, const ViewOptions& view);
    ~RenderLoop();
    RenderLoop(const RenderLoop&) = delete;
    RenderLoop& operator=(const RenderLoop&) = delete;

    // Renders into `film` (which holds `start_spp` samples per pixel already)
    // through `render`, `samples_per_call` samples at a time, up to `max_spp`
    // or an earlier halt condition; prints on stderr why it stopped, unless
    // at max_spp.
    RenderLoopResult run(Film& film, std::uint32_t max_spp, std::uint32_t samples_per_call,
                         const RenderCall& render, std::uint32_t start_spp = 0);

  private:
    RenderLoopOptions options_;
    ViewOptions view_;
    std::unique_ptr<PreviewServer> preview_;
};

} // namespace wp
