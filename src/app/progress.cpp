#include "app/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace wp {
namespace {

std::string format_duration(double seconds) {
    char buffer[32];
    if (seconds < 60.0)
        std::snprintf(buffer, sizeof buffer, "%.1fs", seconds);
    else if (seconds < 3600.0)
        std::snprintf(buffer, sizeof buffer, "%dm%02ds", static_cast<int>(seconds) / 60,
                      static_cast<int>(seconds) % 60);
    else
        std::snprintf(buffer, sizeof buffer, "%dh%02dm", static_cast<int>(seconds / 3600.0),
                      static_cast<int>(seconds / 60.0) % 60);
    return buffer;
}

// "12.3/64 spp" or, without an spp bound, "12.3 spp".
std::string format_samples(const ProgressState& state) {
    char buffer[64];
    if (state.spp_goal > 0)
        std::snprintf(buffer, sizeof buffer, "%.1f/%u spp", state.spp_done, state.spp_goal);
    else
        std::snprintf(buffer, sizeof buffer, "%.1f spp", state.spp_done);
    return buffer;
}

std::string format_error(const ProgressState& state) {
    if (state.rel_mse < 0.0)
        return "";
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, ", relMSE %.3g", state.rel_mse);
    return buffer;
}

} // namespace

ProgressStyle progress_style_for_stderr(bool quiet) {
    if (quiet)
        return ProgressStyle::Off;
    return isatty(STDERR_FILENO) != 0 ? ProgressStyle::Terminal : ProgressStyle::Lines;
}

ProgressReport::ProgressReport(ProgressStyle style)
    : style_(style), last_output_(std::chrono::steady_clock::now()) {}

ProgressReport::~ProgressReport() {
    finish();
}

void ProgressReport::update(const ProgressState& state) {
    if (style_ == ProgressStyle::Off)
        return;
    // The part of the way done, in time: elapsed / (elapsed + left), which
    // for an spp bound alone is spp_done / spp_goal.
    const double total = state.elapsed_seconds + state.seconds_left;
    const double fraction =
        state.seconds_left >= 0.0 && total > 0.0 ? state.elapsed_seconds / total : 0.0;
    if (style_ == ProgressStyle::Terminal)
        draw_terminal(state, fraction, false);
    else
        print_line(state, fraction);
}

void ProgressReport::draw_terminal(const ProgressState& state, double fraction, bool at_once) {
    const auto now = std::chrono::steady_clock::now();
    if (!at_once && drawn_ && now - last_output_ < std::chrono::milliseconds(100)) {
        // Redraw at most ten times a second; the last state waits for finish().
        pending_ = true;
        latest_ = state;
        latest_fraction_ = fraction;
        return;
    }
    last_output_ = now;
    drawn_ = true;
    pending_ = false;
    constexpr int width = 30;
    const int filled = std::clamp(static_cast<int>(width * fraction), 0, width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    const std::string left =
        state.seconds_left >= 0.0 ? "  ETA " + format_duration(state.seconds_left) : "";
    // \033[K clears what a longer earlier line left on the right.
    std::fprintf(stderr, "\r[%s] %s  %s  %.3g samples/s%s%s\033[K", bar.c_str(),
                 format_samples(state).c_str(), format_duration(state.elapsed_seconds).c_str(),
                 state.samples_per_second, left.c_str(), format_error(state).c_str());
    std::fflush(stderr);
}

void ProgressReport::print_line(const ProgressState& state, double fraction) {
    const auto now = std::chrono::steady_clock::now();
    const int tenths = static_cast<int>(std::floor(fraction * 10.0));
    if (tenths <= tenths_printed_ && now - last_output_ < std::chrono::seconds(5))
        return;
    last_output_ = now;
    tenths_printed_ = std::max(tenths, tenths_printed_);
    const std::string done = state.seconds_left >= 0.0
                                 ? " (" + std::to_string(static_cast<int>(fraction * 100.0)) + "%)"
                                 : "";
    const std::string left =
        state.seconds_left >= 0.0 ? ", " + format_duration(state.seconds_left) + " left" : "";
    std::fprintf(stderr, "wavepath: progress: %s%s, %s, %.3g samples/s%s%s\n",
                 format_samples(state).c_str(), done.c_str(),
                 format_duration(state.elapsed_seconds).c_str(), state.samples_per_second,
                 left.c_str(), format_error(state).c_str());
    std::fflush(stderr);
}

void ProgressReport::finish() {
    if (pending_)
        draw_terminal(latest_, latest_fraction_, true);
    if (style_ == ProgressStyle::Terminal && drawn_)
        std::fputc('\n', stderr);
    drawn_ = false;
}

} // namespace wp
