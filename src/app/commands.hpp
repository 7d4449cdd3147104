// The subcommands of the `wavepath` executable.
#pragma once

#include <cstdint>
#include <string>

#include "image/tonemap.hpp"

namespace wp {

struct RenderCommand {
    std::string scene;
    std::string out = "render.exr"; // format from the extension: .exr, .pfm or .png
    std::string png;                // optional extra PNG view
    std::string device;             // selector; empty picks the default
    std::uint32_t spp = 16;
    std::uint32_t seed = 0;
    int width = 0; // 0 keeps the scene's resolution
    int height = 0;
    std::uint32_t max_depth = 1024;
    bool general = false;
    bool regeneration = false;
    std::uint32_t pool = 0; // path slots; 0: one per pixel
    bool profile = false;   // print the per-stage table
    std::string profile_json;
    std::string trace;
    ViewOptions view;
};

struct BenchCommand {
    std::string scene = "scenes/hexroom.json";
    std::string device;
    int size = 512; // the rendered workload is size x size
    std::uint32_t spp = 8;
    int repetitions = 5; // launches of each stage-alone workload
};

int run_devices();
int run_bench(const BenchCommand& command);
int run_render(const RenderCommand& command);

} // namespace wp
