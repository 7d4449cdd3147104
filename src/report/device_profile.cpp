#include "report/device_profile.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "cl/memory_bandwidth.hpp"
#include "util/file.hpp"
#include "util/format.hpp"

namespace wp {
namespace {

// The context with the copy bandwidth of local device `d` (measured once per
// process), or 0 for a device that failed.
ProfileContext with_bandwidth(const ProfileContext& context, const MultiDeviceRenderer& renderer,
                              std::size_t d) {
    ProfileContext own = context;
    const WavefrontIntegrator* integrator = renderer.integrator(d);
    own.memory_bandwidth = integrator ? measured_copy_bandwidth(integrator->device()) : 0.0;
    return own;
}

} // namespace

std::string device_share_table(const std::vector<DeviceShare>& shares) {
    std::uint64_t total = 0;
    for (const DeviceShare& share : shares)
        total += share.samples;
    std::string out =
        format_text("%-4s %-5s %-40s %12s %7s %11s %9s %9s %6s\n", "rank", "index", "device",
                    "samples", "share", "samples/s", "busy s", "idle s", "chunks");
    for (const DeviceShare& share : shares) {
        out += format_text(
            "%-4d %-5s %-40.40s %12llu %6.1f%% %11.4g %9.3f %9.3f %6u\n", share.rank,
            share.index.c_str(), share.name.c_str(), static_cast<unsigned long long>(share.samples),
            total ? 100.0 * static_cast<double>(share.samples) / static_cast<double>(total) : 0.0,
            share.samples_per_second(), share.busy_seconds, share.idle_seconds, share.chunks);
        if (!share.error.empty())
            out += "     failed: " + share.error + "\n";
    }
    return out;
}

nlohmann::json device_share_json(const std::vector<DeviceShare>& shares) {
    std::uint64_t total = 0;
    for (const DeviceShare& share : shares)
        total += share.samples;
    nlohmann::json out = nlohmann::json::array();
    for (const DeviceShare& share : shares)
        out.push_back(
            {{"rank", share.rank},
             {"host", share.host},
             {"index", share.index},
             {"name", share.name},
             {"samples", share.samples},
             {"share",
              total ? static_cast<double>(share.samples) / static_cast<double>(total) : 0.0},
             {"samples_per_second", share.samples_per_second()},
             {"busy_seconds", share.busy_seconds},
             {"idle_seconds", share.idle_seconds},
             {"chunks", share.chunks},
             {"failed", !share.error.empty()},
             {"error", share.error}});
    return out;
}

std::string multi_device_profile_table(const MultiDeviceRenderer& renderer,
                                       const ProfileContext& context) {
    const std::vector<DeviceShare> shares = renderer.shares();
    if (shares.size() == 1)
        return profile_table(renderer.profiler(0), renderer.device_stats(0),
                             with_bandwidth(context, renderer, 0)) +
               "\n" + device_share_table(shares);
    std::string out;
    for (std::size_t d = 0; d < renderer.local_device_count(); ++d) {
        ProfileContext own = with_bandwidth(context, renderer, d);
        own.device = shares[d].name + " (" + shares[d].index + ")";
        out += profile_table(renderer.profiler(d), renderer.device_stats(d), own) + "\n";
    }
    return out +
           format_text(
               "split of %dx%d at %u spp over %zu devices (by demand, in chunks of samples):\n",
               context.width, context.height, context.spp, shares.size()) +
           device_share_table(shares);
}

nlohmann::json multi_device_profile_json(const MultiDeviceRenderer& renderer,
                                         const ProfileContext& context) {
    const std::vector<DeviceShare> shares = renderer.shares();
    const std::size_t local = renderer.local_device_count();
    const ProfileContext first = with_bandwidth(context, renderer, 0);
    nlohmann::json out = profile_json(renderer.profiler(0), renderer.stats(), first);
    nlohmann::json devices = device_share_json(shares);
    std::vector<StageTotals> sum(kStageCount);
    double busy = 0.0;
    for (std::size_t d = 0; d < local; ++d) {
        const Profiler& profiler = renderer.profiler(d);
        std::vector<StageTotals> totals = profiler.totals();
        for (int s = 0; s < kStageCount; ++s) {
            sum[s].launches += totals[s].launches;
            sum[s].items += totals[s].items;
            sum[s].device_seconds += totals[s].device_seconds;
        }
        busy += profiler.device_busy_seconds();
        const double bandwidth = with_bandwidth(context, renderer, d).memory_bandwidth;
        devices[d]["stages"] = stages_json(totals, bandwidth);
        devices[d]["copy_bandwidth_gigabytes_per_second"] = bandwidth * 1e-9;
        devices[d]["device_busy_seconds"] = profiler.device_busy_seconds();
    }
    out["stages"] = stages_json(sum, first.memory_bandwidth); // against the first device's copy
    out["device_busy_seconds"] = busy;
    out["devices"] = devices;
    return out;
}

void write_multi_device_profile_json(const std::filesystem::path& path,
                                     const MultiDeviceRenderer& renderer,
                                     const ProfileContext& context) {
    std::string text = multi_device_profile_json(renderer, context).dump(2) + "\n";
    write_bytes_atomically(path, text.data(), text.size());
}

void write_multi_device_trace(const std::filesystem::path& path,
                              const MultiDeviceRenderer& renderer) {
    const std::vector<DeviceShare> shares = renderer.shares();
    if (renderer.local_device_count() == 1) {
        renderer.profiler(0).write_trace(path, shares[0].name);
        return;
    }
    nlohmann::json events = nlohmann::json::array();
    for (std::size_t d = 0; d < renderer.local_device_count(); ++d)
        // Each device has its own clock: its time starts at its first record.
        renderer.profiler(d).append_trace_events(events, static_cast<int>(d) + 1,
                                                 "wavepath on " + shares[d].name + " (" +
                                                     shares[d].index + ")");
    write_trace_file(path, events);
}

} // namespace wp
