// A one-line progress bar on stderr: samples done, elapsed time, samples per
// second and the estimated time left. Silent when stderr is not a terminal,
// so logs and pipes get no control characters.
#pragma once

#include <chrono>
#include <cstdint>

namespace wp {

class ProgressBar {
  public:
    ProgressBar(std::uint64_t total, std::uint64_t pixels_per_sample);
    ~ProgressBar();
    void update(double samples_per_pixel_done);
    void finish();

  private:
    std::uint64_t total_;
    std::uint64_t pixels_;
    bool enabled_;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_{};
};

} // namespace wp
