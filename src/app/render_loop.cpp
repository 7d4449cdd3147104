#include "app/render_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <iostream>
#include <numeric>

#include <CLI/CLI.hpp>

#include "app/cli_options.hpp" // cli_limits
#include "app/interrupt.hpp"
#include "app/preview_server.hpp"
#include "app/progress.hpp"
#include "image/metrics.hpp"
#include "image/png.hpp"
#include "util/format.hpp"

namespace wp {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double>(to - from).count();
}

// A JSON number, or null for "not known" (negative).
std::string json_number(double value) {
    return value < 0.0 || !std::isfinite(value) ? "null" : format_text("%.6g", value);
}

// The estimate costs two half images and a pass over them; it is made
// again only once the rendering since the last one took this many times as
// long, so that it never takes more than a few percent of the time. On
// small images it is made after every call.
constexpr double kEstimateCostRatio = 20.0;
// Likewise for the preview's PNG, and at most once a second.
constexpr double kPreviewCostRatio = 10.0;
constexpr double kPreviewInterval = 1.0;
// The next call's time is predicted from the mean of the last few.
constexpr std::size_t kCallsForPrediction = 8;

// The estimate from a film of `spp` (>= 2) samples per pixel in every pixel:
// its even and odd sample indices 0 .. spp-1 are the two halves, ceil(spp/2)
// and floor(spp/2) of them.
double rel_mse_estimate(const Film& film, std::uint32_t spp) {
    return rel_mse_from_halves(film.half_mean(0), film.half_mean(1), spp - spp / 2, spp / 2);
}

// Why the render stopped, on stderr (the caller reports an interrupt, and
// reaching the spp bound needs no word unless a target error was missed).
void print_halt(const RenderLoopResult& result, const RenderLoopOptions& options,
                std::uint32_t max_spp) {
    const std::string estimate = result.estimate.spp > 0
                                     ? "estimated relMSE " +
                                           format_text("%.4g", result.estimate.rel_mse) + " at " +
                                           std::to_string(result.estimate.spp) + " spp"
                                     : "";
    switch (result.reason) {
    case HaltReason::TimeBudget:
        std::cerr << "wavepath: time budget of " << format_text("%g", options.time_budget)
                  << " s reached: " << result.spp << " spp in "
                  << format_text("%.2f", result.seconds) << " s\n";
        break;
    case HaltReason::TargetError:
        std::cerr << "wavepath: target error " << format_text("%g", options.target_error)
                  << " reached: " << estimate;
        if (result.previous.spp > 0)
            std::cerr << " (" << format_text("%.4g", result.previous.rel_mse) << " at "
                      << result.previous.spp << " spp)";
        std::cerr << ", " << format_text("%.2f", result.seconds) << " s\n";
        break;
    case HaltReason::SampleCount:
        if (options.target_error > 0.0)
            std::cerr << "wavepath: the target error " << format_text("%g", options.target_error)
                      << " was not reached within " << max_spp << " spp"
                      << (estimate.empty() ? "" : ": " + estimate) << "\n";
        break;
    case HaltReason::Interrupted:
        break; // the caller says what the outputs hold
    }
}

} // namespace

void add_render_loop_options(CLI::App& render, RenderLoopOptions& options, std::uint32_t& spp) {
    const CLI::Validator positive(
        [](const std::string& text) -> std::string {
            double value = 0.0;
            if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value <= 0.0)
                return "expected a positive number, got '" + text + "'";
            return {};
        },
        "POSITIVE");
    render
        .add_option("--time", options.time_budget,
                    "Stop at this many seconds of rendering (kernel build excluded): the render "
                    "ends before the call that would pass it. Without --spp, samples per pixel "
                    "are unbounded (up to the largest --spp); with it, the first condition met "
                    "(--spp, --time, --target-error) ends the render")
        ->check(positive);
    render
        .add_option("--target-error", options.target_error,
                    "Stop when the relMSE estimated from the even and odd half images falls "
                    "below this (checked from 2 spp on); combines with --spp and --time as "
                    "--time does")
        ->check(positive);
    render.add_flag("--quiet,-q", options.quiet, "No progress report on stderr");
    CLI::Option* preview =
        render
            .add_option(
                "--preview", options.preview_port,
                "Serve a live preview of the render (the image, spp, speed, error, a stop "
                "button) at http://127.0.0.1:PORT/TOKEN/ (TOKEN: drawn per run, printed with "
                "the URL); 0 picks a free port")
            ->expected(0, 1)
            ->default_str(std::to_string(kDefaultPreviewPort))
            ->check(CLI::Range(0, 65535));
    render
        .add_option("--preview-bind", options.preview_bind,
                    "The address the preview listens on (0.0.0.0: every interface; the page "
                    "can stop the render, so only on a trusted network)")
        ->capture_default_str()
        ->needs(preview); // alone it would be ignored
    CLI::Option* spp_option = render.get_option("--spp");
    spp_option->description("Samples per pixel. With --time or --target-error, a bound on them "
                            "only if given: the first of the three conditions met ends the render");
    render.parse_complete_callback([&options, &spp, spp_option] {
        options.spp_given = spp_option->count() > 0;
        if (!options.spp_given && (options.time_budget > 0.0 || options.target_error > 0.0))
            spp = cli_limits::max_samples_per_pixel;
    });
}

std::string describe_halt_conditions(const RenderLoopOptions& options, std::uint32_t spp) {
    std::vector<std::string> parts;
    const bool others = options.time_budget > 0.0 || options.target_error > 0.0;
    if (options.spp_given || !others)
        parts.push_back("at " + std::to_string(spp) + " spp");
    if (options.time_budget > 0.0)
        parts.push_back("for " + format_text("%g", options.time_budget) + " s");
    if (options.target_error > 0.0)
        parts.push_back("until the estimated relMSE is below " +
                        format_text("%g", options.target_error));
    std::string text;
    for (const std::string& part : parts)
        text += (text.empty() ? "" : " or ") + part;
    return parts.size() > 1 ? text + ", whichever comes first" : text;
}

RenderLoop::RenderLoop(const RenderLoopOptions& options, const ViewOptions& view)
    : options_(options), view_(view) {
    if (options_.preview_port < 0)
        return;
    preview_ = std::make_unique<PreviewServer>(options_.preview_bind, options_.preview_port);
    std::cerr << "wavepath: preview at " << preview_->url()
              << " (its Stop button ends the render as Ctrl-C does)\n";
}

RenderLoop::~RenderLoop() = default;

RenderLoopResult RenderLoop::run(Film& film, std::uint32_t max_spp, std::uint32_t samples_per_call,
                                 const RenderCall& render, std::uint32_t start_spp) {
    const Clock::time_point start = Clock::now();
    const double pixels = static_cast<double>(film.pixel_count());
    const double time_budget = options_.time_budget;
    const double target = options_.target_error;
    const ProgressStyle style = progress_style_for_stderr(options_.quiet);
    ProgressReport progress(style);
    // Someone reads the estimate: the target, the preview or the progress.
    const bool want_estimate = target > 0.0 || preview_ || style != ProgressStyle::Off;
    // The spp bound is shown only when it is one the user chose.
    const bool spp_bounded = options_.spp_given || (time_budget <= 0.0 && target <= 0.0);
    const std::uint32_t spp_goal = spp_bounded ? max_spp : 0;

    RenderLoopResult result;
    result.spp = start_spp;
    std::deque<double> recent_calls; // seconds from one call's start to the next's
    double rendered_since_estimate = 0.0, estimate_cost = 0.0, preview_cost = 0.0;
    Clock::time_point last_preview{};

    // What the loop knows at `spp_done` samples per pixel, `elapsed` seconds in.
    const auto state_at = [&](double spp_done, double elapsed) {
        ProgressState state;
        state.spp_done = spp_done;
        state.spp_goal = spp_goal;
        state.elapsed_seconds = elapsed;
        const double spp_rate = elapsed > 0.0 ? (spp_done - start_spp) / elapsed : 0.0;
        state.samples_per_second = spp_rate * pixels;
        // The first condition met ends the render, so the time left is the
        // least of each condition's.
        double left = -1.0;
        const auto consider = [&left](double seconds) {
            seconds = std::max(0.0, seconds);
            left = left < 0.0 ? seconds : std::min(left, seconds);
        };
        if (spp_rate > 0.0)
            consider((max_spp - spp_done) / spp_rate);
        if (time_budget > 0.0)
            consider(time_budget - elapsed);
        if (result.estimate.spp > 0) {
            state.rel_mse = result.estimate.rel_mse;
            // relMSE falls as 1/spp: the spp at which it reaches the target.
            if (target > 0.0 && spp_rate > 0.0)
                consider((result.estimate.spp * result.estimate.rel_mse / target - spp_done) /
                         spp_rate);
        }
        state.seconds_left = left;
        return state;
    };
    const auto status_json = [&](const ProgressState& state, const char* phase) {
        return "{\"spp\": " + std::to_string(result.spp) +
               ", \"spp_goal\": " + std::to_string(spp_goal) +
               ", \"width\": " + std::to_string(film.width()) +
               ", \"height\": " + std::to_string(film.height()) +
               ", \"elapsed_seconds\": " + json_number(state.elapsed_seconds) +
               ", \"samples_per_second\": " + json_number(state.samples_per_second) +
               ", \"seconds_left\": " + json_number(state.seconds_left) +
               ", \"rel_mse\": " + json_number(state.rel_mse) + ", \"state\": \"" + phase + "\"}";
    };
    const auto publish_preview = [&](const ProgressState& state, const char* phase) {
        const Clock::time_point encode_start = Clock::now();
        preview_->publish(encode_png(film.mean(), view_), status_json(state, phase));
        last_preview = Clock::now();
        preview_cost = seconds_between(encode_start, last_preview);
    };

    while (true) {
        if (result.spp >= max_spp) {
            result.reason = HaltReason::SampleCount;
            break;
        }
        if (result.spp > start_spp) { // at least one call
            if (interrupt_requested()) {
                result.reason = HaltReason::Interrupted;
                break;
            }
            if (target > 0.0 && result.estimate.spp == result.spp &&
                result.estimate.rel_mse < target) {
                result.reason = HaltReason::TargetError;
                break;
            }
            const double mean_call =
                std::accumulate(recent_calls.begin(), recent_calls.end(), 0.0) /
                static_cast<double>(recent_calls.size());
            if (time_budget > 0.0 &&
                seconds_between(start, Clock::now()) + mean_call > time_budget) {
                result.reason = HaltReason::TimeBudget;
                break;
            }
        }
        const Clock::time_point call_start = Clock::now();
        const std::uint32_t first = result.spp;
        // Calls end on multiples of samples_per_call, also after resuming
        // from a checkpoint that ended short of one (render/checkpoint.hpp),
        // so that a resumed film is summed as the uninterrupted one was.
        const std::uint32_t part =
            std::min(samples_per_call - first % samples_per_call, max_spp - first);
        render(first, part, [&](double done) {
            progress.update(state_at(first + done, seconds_between(start, Clock::now())));
        });
        result.spp += part;
        rendered_since_estimate += seconds_between(call_start, Clock::now());

        if (want_estimate && result.spp >= 2 &&
            rendered_since_estimate >= kEstimateCostRatio * estimate_cost) {
            const Clock::time_point estimate_start = Clock::now();
            result.previous = result.estimate;
            result.estimate = {result.spp, rel_mse_estimate(film, result.spp)};
            estimate_cost = seconds_between(estimate_start, Clock::now());
            rendered_since_estimate = 0.0;
        }
        const Clock::time_point now = Clock::now();
        const ProgressState state = state_at(result.spp, seconds_between(start, now));
        progress.update(state);
        if (preview_ && seconds_between(last_preview, now) >=
                            std::max(kPreviewInterval, kPreviewCostRatio * preview_cost))
            publish_preview(state, "rendering");

        recent_calls.push_back(seconds_between(call_start, Clock::now()));
        if (recent_calls.size() > kCallsForPrediction)
            recent_calls.pop_front();
    }
    result.seconds = seconds_between(start, Clock::now());
    progress.finish();
    if (preview_)
        publish_preview(state_at(result.spp, result.seconds),
                        result.interrupted() ? "stopped" : "done");

    print_halt(result, options_, max_spp);
    return result;
}

} // namespace wp
