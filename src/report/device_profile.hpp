// The profile of a render on several devices: each device's stage table,
// and how the samples were split (share, samples/s, idle time per device).
// With one device the table and JSON are those of profile_report.hpp, plus
// the split.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "render/multi_device.hpp"
#include "report/profile_report.hpp"

namespace wp {

// One row per device: rank, index and name, samples and their share,
// samples/s while busy, busy and idle seconds, chunks, and an error if it
// failed.
std::string device_share_table(const std::vector<DeviceShare>& shares);
nlohmann::json device_share_json(const std::vector<DeviceShare>& shares);

// `render --profile`: with one device, profile_table; with several, each
// local device's table (context.device replaced by that device's name)
// followed by the split.
std::string multi_device_profile_table(const MultiDeviceRenderer& renderer,
                                       const ProfileContext& context);

// `render --profile-json`: profile_json's fields, summed over the local
// devices where there are several ("stages", "device_busy_seconds"), and
// "devices": device_share_json, each local device with its own "stages".
nlohmann::json multi_device_profile_json(const MultiDeviceRenderer& renderer,
                                         const ProfileContext& context);
void write_multi_device_profile_json(const std::filesystem::path& path,
                                     const MultiDeviceRenderer& renderer,
                                     const ProfileContext& context);

// `render --trace`: Profiler::write_trace with one process per local device.
void write_multi_device_trace(const std::filesystem::path& path,
                              const MultiDeviceRenderer& renderer);

} // namespace wp
