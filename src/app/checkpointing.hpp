// `wavepath render --checkpoint FILE [--checkpoint-every SECONDS]` and
// `--resume FILE`: where and how often run_render saves its film
// (render/checkpoint.hpp), and the film it starts from.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "render/checkpoint.hpp"
#include "render/film.hpp"

namespace CLI {
class App;
}

namespace wp {

struct CheckpointOptions {
    std::string file;            // save the film here; empty: never
    double every_seconds = 60.0; // between saves while rendering
    std::string resume;          // start from this checkpoint; empty: from nothing
};

// Registers the three options on the render subcommand.
void add_checkpoint_options(CLI::App& render, CheckpointOptions& options);

// The checkpoints of one render.
class RenderCheckpoints {
  public:
    RenderCheckpoints(const CheckpointOptions& options, CheckpointIdentity identity);

    // With --resume: replaces `film` by the checkpoint's and returns its
    // samples per pixel; throws CheckpointError if the checkpoint does not
    // belong to this render or holds more than `requested`. Without: 0.
    std::uint32_t resume(Film& film, std::uint32_t requested) const;

    // Between render() calls: saves once --checkpoint-every seconds have
    // passed since the last save. A failed save is a warning; the render
    // goes on and the previous checkpoint stays.
    void save_if_due(std::uint32_t samples_per_pixel, const Film& film);

    // At the end, or when interrupted: saves now and says so. Throws
    // FileError on failure.
    void save(std::uint32_t samples_per_pixel, const Film& film);

  private:
    void write(std::uint32_t samples_per_pixel, const Film& film);

    CheckpointOptions options_;
    CheckpointIdentity identity_;
    std::chrono::steady_clock::time_point last_save_ = std::chrono::steady_clock::now();
    bool warned_ = false;
};

} // namespace wp
