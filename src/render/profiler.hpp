// Where the time of a render goes, stage by stage.
//
// With a profiler attached, the integrator asks for an OpenCL event for every
// launch and transfer (the queue must have CL_QUEUE_PROFILING_ENABLE) and
// tells the profiler how many items each one processed. Without one, no
// events are created and nothing waits on them: profiling off costs nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "cl/cl.hpp"
#include "cl/stages.hpp"

namespace wp {

// The stage kernels (src/cl/stages.hpp), then host-device transfers.
#define WP_STAGE_ENUM(enum_name, name) enum_name,
enum class Stage { WP_STAGE_KERNELS(WP_STAGE_ENUM) Transfer };
#undef WP_STAGE_ENUM
constexpr int kStageCount = static_cast<int>(kStageKernelNames.size()) + 1;
const char* stage_name(Stage stage);

struct LaunchRecord {
    Stage stage;
    std::uint64_t items = 0;     // work items that did work (bytes for transfers)
    std::uint64_t queued_ns = 0; // device timestamps (CL_PROFILING_COMMAND_*)
    std::uint64_t start_ns = 0;
    std::uint64_t end_ns = 0;
};

struct StageTotals {
    std::uint64_t launches = 0;
    std::uint64_t items = 0;
    double device_seconds = 0.0;
};

class Profiler {
  public:
    // Starts a record; pass the returned event to the enqueue call.
    cl::Event* begin(Stage stage, std::uint64_t items);
    // Corrects the item count of a record once the device has reported it.
    void set_items(std::size_t record, std::uint64_t items) { records_[record].items = items; }
    std::size_t last_record() const { return records_.size() - 1; }
    // Reads the timestamps of every record whose command has completed
    // (call after a synchronisation point; cheap when nothing is pending).
    void resolve_completed();

    const std::vector<LaunchRecord>& records() const { return records_; }
    std::vector<StageTotals> totals() const; // indexed by Stage
    double device_busy_seconds() const;

    // Chrome trace format (one complete event per launch), for Perfetto or
    // chrome://tracing: this profiler's events as process `pid`, named
    // `process_name`, on its own clock (time 0 at its first record) ...
    void append_trace_events(nlohmann::json& events, int pid,
                             const std::string& process_name) const;
    // ... and a whole trace of one device.
    void write_trace(const std::filesystem::path& path, const std::string& device_name) const;

  private:
    std::vector<LaunchRecord> records_;
    std::vector<cl::Event> pending_; // parallel to records_[resolved_ ...]
    std::size_t resolved_ = 0;
};

// Writes a Chrome trace of `events` (see Profiler::append_trace_events).
void write_trace_file(const std::filesystem::path& path, const nlohmann::json& events);

} // namespace wp
