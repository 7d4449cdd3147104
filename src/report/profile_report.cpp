#include "report/profile_report.hpp"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "render/stage_traffic.hpp"
#include "util/file.hpp"
#include "util/format.hpp"

namespace wp {
namespace {

// Rays for the stages that trace them, items otherwise.
bool traces_rays(Stage stage) {
    return stage == Stage::Intersect || stage == Stage::Shadow;
}

// The kernels that only some launch plans run (the fused kernels, the sort
// of --shade-order sorted): rows only when they ran.
bool optional_kernel(Stage stage) {
    return stage == Stage::Bounce || stage == Stage::Wave || stage == Stage::Tail ||
           stage == Stage::ShadeSort;
}

// Queue lengths per iteration, shortened to the first and last few.
std::string queue_summary(const std::vector<std::uint32_t>& lengths) {
    std::string out;
    const std::size_t shown = 8;
    for (std::size_t i = 0; i < lengths.size(); ++i) {
        if (lengths.size() > 2 * shown && i == shown) {
            out += " ...";
            i = lengths.size() - shown;
        }
        if (!out.empty())
            out += ' ';
        out += std::to_string(lengths[i]);
    }
    return out;
}

// Bytes per second a stage moved: its items times its bytes per item.
double stage_bytes_per_second(Stage stage, const StageTotals& t) {
    return t.device_seconds > 0
               ? static_cast<double>(t.items) * static_cast<double>(stage_bytes_per_item(stage)) /
                     t.device_seconds
               : 0.0;
}

} // namespace

nlohmann::json stage_json(Stage stage, const StageTotals& totals, double memory_bandwidth) {
    nlohmann::json row = {{"stage", stage_name(stage)},
                          {"launches", totals.launches},
                          {"items", totals.items},
                          {"device_seconds", totals.device_seconds}};
    if (stage != Stage::Transfer) {
        const double moved = stage_bytes_per_second(stage, totals);
        row["bytes_per_item"] = stage_bytes_per_item(stage);
        row["gigabytes_per_second"] = moved * 1e-9;
        row["fraction_of_copy_bandwidth"] = memory_bandwidth > 0 ? moved / memory_bandwidth : 0.0;
    }
    return row;
}

nlohmann::json stages_json(const std::vector<StageTotals>& totals, double memory_bandwidth) {
    nlohmann::json stages = nlohmann::json::array();
    for (int s = 0; s < kStageCount; ++s) {
        const Stage stage = static_cast<Stage>(s);
        // The optional kernels only when they ran, as in the table.
        if (optional_kernel(stage) && totals[s].launches == 0)
            continue;
        stages.push_back(stage_json(stage, totals[s], memory_bandwidth));
    }
    return stages;
}

std::string profile_table(const Profiler& profiler, const RenderStats& stats,
                          const ProfileContext& context) {
    std::vector<StageTotals> totals = profiler.totals();
    const double busy = profiler.device_busy_seconds();
    const double wall = stats.render_seconds;
    std::string out;
    out += format_text(
        "profile: %s, %dx%d, %u spp on %s (%s, pool %u%s%s)\n", context.scene.c_str(),
        context.width, context.height, context.spp, context.device.c_str(),
        context.regeneration ? "regeneration" : "one wave at a time", context.pool_size,
        context.launch_plan.empty() ? "" : ", launch plan ", context.launch_plan.c_str());
    out +=
        format_text("%-12s %9s %14s %11s %7s %16s %13s %7s %8s %7s\n", "stage", "launches", "items",
                    "device ms", "share", "rate", "items/launch", "B/item", "GB/s", "of copy");
    for (int s = 0; s < kStageCount; ++s) {
        const StageTotals& t = totals[s];
        Stage stage = static_cast<Stage>(s);
        // The optional kernels' rows only when they ran; with a fused plan,
        // only the kernels that ran (the wave plan's one kernel holds every
        // stage).
        const bool fused_plan = context.launch_plan == "bounce" || context.launch_plan == "wave";
        if (t.launches == 0 && stage != Stage::Transfer && (optional_kernel(stage) || fused_plan))
            continue;
        double rate = t.device_seconds > 0 ? static_cast<double>(t.items) / t.device_seconds : 0.0;
        std::string rate_text = stage == Stage::Transfer ? format_text("%.3g MB/s", rate / 1e6)
                                : traces_rays(stage)     ? format_text("%.3f Mrays/s", rate / 1e6)
                                                         : format_text("%.3f M/s", rate / 1e6);
        double per_launch =
            t.launches ? static_cast<double>(t.items) / static_cast<double>(t.launches) : 0.0;
        out += format_text("%-12s %9llu %14llu %11.1f %6.1f%% %16s %13.0f", stage_name(stage),
                           static_cast<unsigned long long>(t.launches),
                           static_cast<unsigned long long>(t.items), t.device_seconds * 1e3,
                           busy > 0 ? 100.0 * t.device_seconds / busy : 0.0, rate_text.c_str(),
                           per_launch);
        if (stage != Stage::Transfer) {
            // The speed of light: the bytes the stage moved per second against
            // what a copy kernel moves on this device.
            const double moved = stage_bytes_per_second(stage, t);
            const std::string of_copy =
                context.memory_bandwidth > 0
                    ? format_text("%.1f%%", 100.0 * moved / context.memory_bandwidth)
                    : std::string("-");
            out += format_text(" %7llu %8.2f %7s",
                               static_cast<unsigned long long>(stage_bytes_per_item(stage)),
                               moved * 1e-9, of_copy.c_str());
        }
        out += "\n";
    }
    out += format_text("%-12s %9s %14s %11.1f %7s %16s\n", "host (film)", "", "",
                       stats.host_seconds * 1e3, "", "");
    const double samples = static_cast<double>(stats.camera_rays);
    out += format_text(
        "rays: %llu camera + %llu bounce + %llu shadow = %llu\n",
        static_cast<unsigned long long>(stats.camera_rays),
        static_cast<unsigned long long>(stats.bounce_rays),
        static_cast<unsigned long long>(stats.shadow_rays),
        static_cast<unsigned long long>(stats.camera_rays + stats.bounce_rays + stats.shadow_rays));
    out += format_text("samples/s: %.4g; wall %.3f s, device busy %.3f s (%.1f%%), launch and sync "
                       "overhead %.3f s\n",
                       wall > 0 ? samples / wall : 0.0, wall, busy,
                       wall > 0 ? 100.0 * busy / wall : 0.0, wall - busy - stats.host_seconds);
    if (context.memory_bandwidth > 0)
        out += format_text(
            "memory bound: a copy kernel moves %.2f GB/s on this device (read + write); "
            "B/item is global memory per item\n",
            context.memory_bandwidth * 1e-9);
    out += format_text("kernel build: %.3f s%s; options: %s\n", context.build_seconds,
                       context.build_cached ? " (from cache)" : "", context.build_options.c_str());
    out += format_text("iterations: %llu; rays per iteration: ",
                       static_cast<unsigned long long>(stats.iterations)) +
           queue_summary(stats.queue_lengths) + "\n";
    if (!stats.rays_per_bounce.empty()) {
        std::vector<std::uint32_t> per_wave;
        const double waves = std::max(1.0, static_cast<double>(context.spp));
        for (std::uint64_t rays : stats.rays_per_bounce)
            per_wave.push_back(static_cast<std::uint32_t>(static_cast<double>(rays) / waves + 0.5));
        out += "live paths per bounce (mean over waves): " + queue_summary(per_wave) + "\n";
    }
    return out;
}

nlohmann::json profile_json(const Profiler& profiler, const RenderStats& stats,
                            const ProfileContext& context) {
    nlohmann::json stages = stages_json(profiler.totals(), context.memory_bandwidth);
    return {
        {"device", context.device},
        {"scene", context.scene},
        {"width", context.width},
        {"height", context.height},
        {"spp", context.spp},
        {"build_options", context.build_options},
        {"build_seconds", context.build_seconds},
        {"build_cached", context.build_cached},
        {"regeneration", context.regeneration},
        {"pool_size", context.pool_size},
        {"launch_plan", context.launch_plan},
        {"stages", stages},
        {"copy_bandwidth_gigabytes_per_second", context.memory_bandwidth * 1e-9},
        {"host_seconds", stats.host_seconds},
        {"wall_seconds", stats.render_seconds},
        {"device_busy_seconds", profiler.device_busy_seconds()},
        {"rays",
         {{"camera", stats.camera_rays},
          {"bounce", stats.bounce_rays},
          {"shadow", stats.shadow_rays}}},
        {"samples_per_second", stats.render_seconds > 0
                                   ? static_cast<double>(stats.camera_rays) / stats.render_seconds
                                   : 0.0},
        {"iterations", stats.iterations},
        {"queue_lengths", stats.queue_lengths},
        {"rays_per_bounce", stats.rays_per_bounce},
        {"capped_paths", stats.capped_paths},
        {"nonfinite_samples", stats.nonfinite_samples},
    };
}

void write_profile_json(const std::filesystem::path& path, const Profiler& profiler,
                        const RenderStats& stats, const ProfileContext& context) {
    std::string text = profile_json(profiler, stats, context).dump(2) + "\n";
    write_bytes_atomically(path, text.data(), text.size());
}

} // namespace wp
