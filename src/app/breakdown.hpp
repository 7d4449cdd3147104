// `wavepath breakdown` (breakdown.cpp): where a render's error is, by path
// type and near the light or elsewhere (docs/convergence.md, "Where the error
// is"; the arithmetic is report/error_breakdown.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "render/integrator_options.hpp"

namespace wp {

struct BreakdownCommand {
    std::string scene;
    std::string reference;                   // optional: the MSE against it too
    std::vector<std::uint32_t> spp{64, 256}; // checkpoints of one progressive render
    double light_threshold = 10.0;           // brighter pixels see the light
    int light_radius = 2;                    // pixels around them that count as near
    bool total_only = false;                 // no parts: the full estimate's figures alone
    std::string device;
    int width = 0;
    int height = 0;
    IntegratorOptions integrator;
};

CLI::App* add_breakdown_subcommand(CLI::App& app, BreakdownCommand& command);
int run_breakdown(const BreakdownCommand& command);

} // namespace wp
