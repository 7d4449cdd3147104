#include "app/checkpointing.hpp"

#include <iostream>

#include <CLI/CLI.hpp>

#include "app/cli_options.hpp"
#include "util/file.hpp"

namespace wp {

void add_checkpoint_options(CLI::App& render, CheckpointOptions& options) {
    CLI::Option* file = render.add_option(
        "--checkpoint", options.file,
        "Save the film to FILE now and then, and at the end or when interrupted, so "
        "that --resume FILE can go on from it");
    render
        .add_option("--checkpoint-every", options.every_seconds,
                    "Seconds between checkpoints while rendering")
        ->capture_default_str()
        ->check(positive_finite_number)
        ->needs(file); // without it there is nowhere to save: refused, not ignored
    render.add_option("--resume", options.resume,
                      "Start from a checkpoint of the same scene, resolution and options, and "
                      "render up to --spp in all");
}

RenderCheckpoints::RenderCheckpoints(const CheckpointOptions& options, CheckpointIdentity identity)
    : options_(options), identity_(std::move(identity)) {}

std::uint32_t RenderCheckpoints::resume(Film& film, std::uint32_t requested) const {
    if (options_.resume.empty())
        return 0;
    FilmCheckpoint checkpoint = load_checkpoint(options_.resume, identity_);
    if (checkpoint.samples_per_pixel > requested)
        throw CheckpointError("cannot resume from '" + options_.resume + "': it holds " +
                              std::to_string(checkpoint.samples_per_pixel) +
                              " samples per pixel, more than --spp " + std::to_string(requested));
    std::cerr << "wavepath: resuming from '" << options_.resume << "' at "
              << checkpoint.samples_per_pixel << " of " << requested << " samples per pixel\n";
    film = std::move(checkpoint.film);
    return checkpoint.samples_per_pixel;
}

void RenderCheckpoints::save_if_due(std::uint32_t samples_per_pixel, const Film& film) {
    if (options_.file.empty())
        return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_save_).count() < options_.every_seconds)
        return;
    try {
        write(samples_per_pixel, film);
    } catch (const FileError& e) {
        if (!warned_)
            std::cerr << "wavepath: warning: " << e.what() << " (the render goes on)\n";
        warned_ = true;
        last_save_ = now;
    }
}

void RenderCheckpoints::save(std::uint32_t samples_per_pixel, const Film& film) {
    if (options_.file.empty())
        return;
    write(samples_per_pixel, film);
    std::cerr << "wavepath: checkpoint '" << options_.file << "' holds " << samples_per_pixel
              << " samples per pixel (--resume it to go on)\n";
}

void RenderCheckpoints::write(std::uint32_t samples_per_pixel, const Film& film) {
    save_checkpoint(options_.file, identity_, samples_per_pixel, film);
    last_save_ = std::chrono::steady_clock::now();
}

} // namespace wp
