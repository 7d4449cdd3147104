// Progress of a render on stderr: samples per pixel done, samples per
// second, elapsed and remaining time, and the current error estimate.
//
// On a terminal it is one line redrawn in place (at most ten times a
// second); in a log or a pipe, where control characters would be noise, a
// plain line every tenth of the way or every five seconds, whichever comes
// first; with --quiet nothing.
#pragma once

#include <chrono>
#include <cstdint>

namespace wp {

enum class ProgressStyle { Terminal, Lines, Off };

// Terminal when stderr is a terminal, else Lines; Off when quiet.
ProgressStyle progress_style_for_stderr(bool quiet);

// What the render loop (render_loop.hpp) knows at one moment.
struct ProgressState {
    double spp_done = 0.0;      // samples per pixel, fractional within a call
    std::uint32_t spp_goal = 0; // the --spp bound when it is shown; 0: none
    double elapsed_seconds = 0.0;
    double samples_per_second = 0.0;
    // Until the first halt condition is met; negative: not known yet.
    double seconds_left = -1.0;
    // relMSE estimated from the half images (image/metrics.hpp); negative: none yet.
    double rel_mse = -1.0;
};

class ProgressReport {
  public:
    explicit ProgressReport(ProgressStyle style);
    ~ProgressReport();
    ProgressReport(const ProgressReport&) = delete;
    ProgressReport& operator=(const ProgressReport&) = delete;

    void update(const ProgressState& state);
    // Ends the terminal line, so that later messages start on their own.
    void finish();

  private:
    void draw_terminal(const ProgressState& state, double fraction, bool now);
    void print_line(const ProgressState& state, double fraction);

    ProgressStyle style_;
    bool drawn_ = false;
    // Terminal: the latest state, if its drawing was skipped (finish draws it).
    bool pending_ = false;
    ProgressState latest_;
    double latest_fraction_ = 0.0;
    std::chrono::steady_clock::time_point last_output_{};
    int tenths_printed_ = 0; // Lines: the last tenth of the way a line was printed for
};

} // namespace wp
