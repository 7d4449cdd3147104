// Command-line options shared by the subcommands that render or build
// kernels (render, converge, bench, info), registered in one place so that
// every command spells, documents and bounds them the same way.
#pragma once

#include <map>
#include <string>

#include "render/integrator_options.hpp"
#include "scene/scene_read_options.hpp"

#include <CLI/CLI.hpp>

namespace wp {

// Largest values the commands accept; the resolution's comes from the scene
// loader (scene_limits::max_resolution), so a size the CLI takes is a size a
// scene file may hold.
namespace cli_limits {
inline constexpr unsigned max_samples_per_pixel = 1u << 24;
inline constexpr unsigned max_depth = 1u << 20;
} // namespace cli_limits

// Refuses "nan", "inf" and anything else that is not a finite number, for
// options whose value goes into arithmetic (--exposure).
extern const CLI::Validator finite_number;

// Refuses all but positive finite numbers, for durations and thresholds
// (--checkpoint-every, --max-time, --light-threshold): CLI::PositiveNumber
// lets "nan" through, as every comparison with NaN is false.
extern const CLI::Validator positive_finite_number;

// Every field of IntegratorOptions: --seed, --max-depth, --no-nee, --diffuse,
// --light-sampling, --roulette-depth, --roulette, --path-types, --general, --regeneration,
// --pool and --no-cache (which turns options.program_cache off). The defaults shown are options'
// values.
void add_integrator_options(CLI::App& command, IntegratorOptions& options);

// --device: an index P:D or part of a device's name.
void add_device_option(CLI::App& command, std::string& device);
// --device for render: also a comma-separated list of them, or "all"
// (select_devices; docs/multi-device.md).
void add_device_list_option(CLI::App& command, std::string& devices);

// --width and --height, each within the scene loader's resolution limit; 0
// (not given) keeps the scene's resolution.
void add_image_size_options(CLI::App& command, int& width, int& height);

// How a Mitsuba XML scene is read (docs/mitsuba-import.md): -D name=value
// (repeatable), a `$name` as Mitsuba's own -D sets it, and --lenient, which
// replaces or leaves out what wavepath cannot read, with warnings. They go
// to scene_read_options().
void add_scene_options(CLI::App& command);

// This run's -D values and --lenient, for load_scene.
const SceneReadOptions& scene_read_options();

} // namespace wp
