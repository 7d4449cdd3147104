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
    ViewOptions view;
};

int run_devices();
int run_render(const RenderCommand& command);

} // namespace wp
