// What every output of a render records about how it was made: enough to
// know which program, scene and options made an image, and to make it again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/integrator_options.hpp"

namespace wp {

// The SHA-256 of a file's bytes (hex, as sha256sum prints it). Taken when
// the scene is loaded, so that a render records the file it read even if the
// file changes or goes while it runs. Throws FileError if it cannot be read.
std::string file_sha256(const std::string& path);

struct RenderRecord {
    std::string scene_file;   // as given on the command line
    std::string scene_sha256; // file_sha256(scene_file) when it was loaded
    int width = 0;
    int height = 0;
    std::uint32_t samples_done = 0; // per pixel; fewer than asked when interrupted
    std::uint32_t samples_requested = 0;
    std::uint32_t samples_resumed = 0; // per pixel, taken from a checkpoint (--resume)
    IntegratorOptions options;
    std::vector<std::string> devices; // the name of each device that rendered
    std::string launch_plan;          // WavefrontIntegrator::launch_summary() of the first
    double render_seconds = 0.0;      // kernel build excluded
};

// The entries, each named "wavepath.<what>": version, commit (`git describe
// --always --dirty` at build time, "unknown" outside a git checkout), scene,
// scene_sha256 (of the scene file's bytes; the mesh files it names are not
// included), resolution ("WxH"), samples_per_pixel,
// samples_requested, resumed_from (samples_resumed), seed, estimator (describe_estimator),
// max_depth, devices (joined by "; "), launch_plan (plan, regeneration, pool and
// work-group size of the first device; omitted when empty), render_seconds and samples_per_second
// (of this run's samples: a resumed render's time does not include the checkpoint's).
Metadata render_metadata(const RenderRecord& record);

} // namespace wp
