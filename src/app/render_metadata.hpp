// What every output of a render records about how it was made: enough to
// know which program, scene and options made an image, and to make it again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/integrator_options.hpp"

namespace wp {

struct RenderRecord {
    std::string scene_file; // as given on the command line
    int width = 0;
    int height = 0;
    std::uint32_t samples_done = 0; // per pixel; fewer than asked when interrupted
    std::uint32_t samples_requested = 0;
    IntegratorOptions options;
    std::vector<std::string> devices; // the name of each device that rendered
    double render_seconds = 0.0;      // kernel build excluded
};

// The entries, each named "wavepath.<what>": version, commit (`git describe
// --always --dirty` at build time, "unknown" outside a git checkout), scene,
// scene_sha256 (of the scene file's bytes, as sha256sum prints it; the mesh
// files it names are not included), resolution ("WxH"), samples_per_pixel,
// samples_requested, seed, estimator (describe_estimator), max_depth,
// devices (joined by "; "), render_seconds and samples_per_second. Throws
// FileError if the scene file can no longer be read.
Metadata render_metadata(const RenderRecord& record);

} // namespace wp
