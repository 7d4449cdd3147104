// The subcommands of the `wavepath` executable.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "app/checkpointing.hpp"
#include "app/render_loop.hpp"
#include "image/exr.hpp"
#include "image/tonemap.hpp"
#include "render/film.hpp"
#include "render/integrator_options.hpp"
#include "scene/scene.hpp"

namespace CLI {
class App;
}

namespace wp {

struct RenderCommand {
    std::string scene;
    std::string out = "render.exr"; // format from the extension: .exr, .pfm or .png
    std::string png;                // optional extra PNG view
    std::string device;             // selector; empty picks the default
    std::uint32_t spp = 16;
    int width = 0; // 0 keeps the scene's resolution
    int height = 0;
    IntegratorOptions integrator;
    bool profile = false; // print the per-stage table
    std::string profile_json;
    std::string trace;
    std::string variance; // optional: each pixel's variance of the mean (.exr or .pfm)
    ViewOptions view;
    RenderLoopOptions loop;        // --time, --target-error, --quiet, --preview (render_loop.hpp)
    CheckpointOptions checkpoints; // --checkpoint, --checkpoint-every, --resume
};

struct BenchCommand {
    std::string scene = "scenes/hexroom.json";
    std::string device;
    int size = 512; // the rendered workload is size x size
    std::uint32_t spp = 8;
    int repetitions = 5; // launches of each stage-alone workload
    // The rendered workload runs with regeneration on and off, whatever this says.
    IntegratorOptions integrator;
};

// Convergence reports (docs/convergence.md): converge.cpp and compare.cpp.
struct ConvergeCommand {
    std::string scene;
    std::string reference;             // .exr or .pfm; empty: error from the half images
    std::string csv;                   // optional outputs
    std::string plot;                  // SVG
    std::string out;                   // the final image
    std::vector<std::string> overlays; // earlier CSVs drawn in the same plot
    bool replot = false;               // plot the overlays only, render nothing
    std::string title;                 // of the plot
    std::string device;
    std::uint32_t max_spp = 0; // with max_time 0 too: 256
    double max_time = 0.0;     // seconds of render time
    int width = 0;
    int height = 0;
    IntegratorOptions integrator;
    ViewOptions view; // of --out, when it is a .png
};

struct CompareCommand {
    std::string image;
    std::string reference;
    std::string diff; // optional: .png false colour, .exr/.pfm the raw map
    // Optional: the two images' variances of the mean (render --variance), for
    // a test that their difference is noise: |z| at most `sigma` for the
    // whole image and every block of 16x16 pixels, per channel.
    std::vector<std::string> variances;
    double sigma = 5.0;
};

// Register the subcommands' options (each in its command's file; the options
// of every command that renders come from cli_options.hpp).
CLI::App* add_render_subcommand(CLI::App& app, RenderCommand& command);
CLI::App* add_bench_subcommand(CLI::App& app, BenchCommand& command);
CLI::App* add_converge_subcommand(CLI::App& app, ConvergeCommand& command);
CLI::App* add_compare_subcommand(CLI::App& app, CompareCommand& command);
int run_converge(const ConvergeCommand& command);
int run_compare(const CompareCommand& command);

// `wavepath info` (info.cpp): a scene's counts, features, build options and
// build times (docs/specialization.md).
struct InfoCommand {
    std::string scene;
    std::string device;
    IntegratorOptions integrator; // the build options follow the estimator
};
CLI::App* add_info_subcommand(CLI::App& app, InfoCommand& command);
int run_info(const InfoCommand& command);

// `wavepath kernel-source` (info.cpp; hidden, for .ci/gpu-targets-check): the
// build options a render of a scene passes the OpenCL compiler, on stdout,
// and the program text it compiles, includes expanded as the host does, to a
// file; no OpenCL device is needed.
struct KernelSourceCommand {
    std::string scene;
    std::string source; // where to write the expanded program text
    IntegratorOptions integrator;
};
CLI::App* add_kernel_source_subcommand(CLI::App& app, KernelSourceCommand& command);
int run_kernel_source(const KernelSourceCommand& command);

// `wavepath export-mitsuba` (export_mitsuba.cpp): the scene as a Mitsuba 3
// scene (docs/mitsuba-export.md).
struct ExportMitsubaCommand {
    std::string scene;
    std::string out; // .xml; the meshes go beside it
    std::uint32_t spp = 64;
    int width = 0; // 0 keeps the scene's resolution
    int height = 0;
};
CLI::App* add_export_mitsuba_subcommand(CLI::App& app, ExportMitsubaCommand& command);
int run_export_mitsuba(const ExportMitsubaCommand& command);

// The extensions write_image knows.
inline const std::vector<std::string> kImageExtensions = {".exr", ".pfm", ".png"};

// Fails before rendering, not after, if an output cannot be written: throws
// FileError unless check_writable(path) passes (util/file.hpp) and, when
// `extensions` is not empty, its extension (in any case) is one of them. ""
// (no output) passes.
void check_output(const std::string& path, const std::vector<std::string>& extensions = {});

// A file a command reads or writes, with the words that name it in messages
// ("--png", "the scene").
struct NamedPath {
    std::string role;
    std::string path;
};

// Fails before any work if an output would destroy an input or another
// output: throws FileError "cannot write <role> '<path>': it is the same file
// as <role> '<path>'" when two of them resolve (symbolic links, "..") to the
// same file. Empty paths (not given) are skipped.
void check_distinct_outputs(const std::vector<NamedPath>& inputs,
                            const std::vector<NamedPath>& outputs);

// Every file the scene read: "the scene" itself and each "input file" (its
// meshes, textures and environment map), for
// check_distinct_outputs once the scene is loaded.
std::vector<NamedPath> scene_inputs(const Scene& scene);

// Writes an image that took long to make; if that fails, saves it to a
// fallback file (in the system's temporary directory) so the work is not
// lost, and throws FileError naming both the failure and the fallback.
// `layers` (an EXR's AOVs) only for an .exr `path`.
void write_result_image(const std::string& path, const Image& image, const ViewOptions& view,
                        std::span<const ExrLayer> layers = {});

// Loads a scene, prints its warnings, and applies --width/--height (0 keeps
// the scene's resolution).
Scene load_scene_for_render(const std::string& path, int width, int height);

// A reference image for errors against it (converge, breakdown): throws one
// line if it cannot be read, is not the render's size, or holds NaN or Inf.
Image read_reference_for(const std::string& path, const Scene& scene);

// The render's film; throws "out of host memory: the film of WxH pixels
// needs N MiB ..." where the allocation fails.
Film allocate_film(int width, int height);

// With `check`, each device's self-check too (render/self_check.hpp) on a
// built-in scene with every feature; exit status 1 if one fails.
int run_devices(bool check = false);
int run_bench(const BenchCommand& command);
int run_render(const RenderCommand& command);

} // namespace wp
