// Turning a profiled render into the table, JSON and numbers users read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "render/profiler.hpp"
#include "render/wavefront.hpp"

namespace wp {

// What the report needs to know about the run besides the profiler.
struct ProfileContext {
    std::string device;
    std::string scene;
    int width = 0;
    int height = 0;
    std::uint32_t spp = 0;
    std::string build_options;
    double build_seconds = 0.0;
    bool build_cached = false;
    bool regeneration = true;
    std::uint32_t pool_size = 0;
    std::string launch_plan; // e.g. "stages"; empty: not said
    // The device's copy bandwidth in bytes/s (cl/memory_bandwidth.hpp), which
    // each stage's memory traffic is compared with; 0: not measured.
    double memory_bandwidth = 0.0;
};

// One stage's row of the JSON: its totals, bytes per item
// (render/stage_traffic.hpp), GB/s, and the fraction of `memory_bandwidth`.
nlohmann::json stage_json(Stage stage, const StageTotals& totals, double memory_bandwidth);
nlohmann::json stages_json(const std::vector<StageTotals>& totals, double memory_bandwidth);

// The per-stage table and the summary below it, as `render --profile` prints.
std::string profile_table(const Profiler& profiler, const RenderStats& stats,
                          const ProfileContext& context);

// The same figures, machine-readable (see docs/profiling.md for the fields).
nlohmann::json profile_json(const Profiler& profiler, const RenderStats& stats,
                            const ProfileContext& context);

void write_profile_json(const std::filesystem::path& path, const Profiler& profiler,
                        const RenderStats& stats, const ProfileContext& context);

} // namespace wp
