#include "app/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace wp {
namespace {

std::string format_duration(double seconds) {
    char buffer[32];
    if (seconds < 60.0)
        std::snprintf(buffer, sizeof buffer, "%.1fs", seconds);
    else
        std::snprintf(buffer, sizeof buffer, "%dm%02ds", static_cast<int>(seconds) / 60,
                      static_cast<int>(seconds) % 60);
    return buffer;
}

} // namespace

ProgressBar::ProgressBar(std::uint64_t total, std::uint64_t pixels_per_sample)
    : total_(total), pixels_(pixels_per_sample), enabled_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
    finish();
}

void ProgressBar::update(double samples_per_pixel_done) {
    const double done = samples_per_pixel_done;
    if (!enabled_ || total_ == 0)
        return;
    auto now = std::chrono::steady_clock::now();
    if (done < static_cast<double>(total_) && now - last_draw_ < std::chrono::milliseconds(100))
        return; // redraw at most ten times a second
    last_draw_ = now;
    double elapsed = std::chrono::duration<double>(now - start_).count();
    const double total = static_cast<double>(total_);
    double rate = elapsed > 0.0 ? done * static_cast<double>(pixels_) / elapsed : 0.0;
    double left = done > 0.0 ? elapsed * (total - done) / done : 0.0;
    constexpr int width = 30;
    int filled = std::clamp(static_cast<int>(width * done / total), 0, width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %.1f/%llu spp  %s  %.3g samples/s  ETA %s   ", bar.c_str(), done,
                 static_cast<unsigned long long>(total_), format_duration(elapsed).c_str(), rate,
                 format_duration(left).c_str());
    std::fflush(stderr);
}

void ProgressBar::finish() {
    if (enabled_ && !finished_)
        std::fputc('\n', stderr);
    finished_ = true;
}

} // namespace wp
