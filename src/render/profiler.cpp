#include "render/profiler.hpp"

#include <nlohmann/json.hpp>

#include "util/file.hpp"

namespace wp {

const char* stage_name(Stage stage) {
    if (stage == Stage::Transfer)
        return "transfers";
    // The names are string literals, so their data are terminated.
    return kStageKernelNames.at(static_cast<std::size_t>(stage)).data();
}

cl::Event* Profiler::begin(Stage stage, std::uint64_t items) {
    records_.push_back({stage, items, 0, 0, 0});
    pending_.emplace_back();
    return &pending_.back();
}

void Profiler::resolve_completed() {
    std::size_t first_pending = resolved_;
    while (resolved_ < records_.size()) {
        cl::Event& event = pending_[resolved_ - first_pending];
        if (event.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>() != CL_COMPLETE)
            break;
        LaunchRecord& r = records_[resolved_];
        r.queued_ns = event.getProfilingInfo<CL_PROFILING_COMMAND_QUEUED>();
        r.start_ns = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
        r.end_ns = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
        ++resolved_;
    }
    // Release the events already read; pending_ then starts at resolved_.
    pending_.erase(pending_.begin(),
                   pending_.begin() + static_cast<std::ptrdiff_t>(resolved_ - first_pending));
}

std::vector<StageTotals> Profiler::totals() const {
    std::vector<StageTotals> out(kStageCount);
    for (const LaunchRecord& r : records_) {
        StageTotals& t = out[static_cast<int>(r.stage)];
        ++t.launches;
        t.items += r.items;
        t.device_seconds += static_cast<double>(r.end_ns - r.start_ns) * 1e-9;
    }
    return out;
}

double Profiler::device_busy_seconds() const {
    double sum = 0.0;
    for (const StageTotals& t : totals())
        sum += t.device_seconds;
    return sum;
}

void Profiler::append_trace_events(nlohmann::json& events, int pid,
                                   const std::string& process_name) const {
    const std::uint64_t origin = records_.empty() ? 0 : records_.front().queued_ns;
    events.push_back(
        {{"name", "process_name"}, {"ph", "M"}, {"pid", pid}, {"args", {{"name", process_name}}}});
    for (const LaunchRecord& r : records_) {
        if (r.end_ns == 0)
            continue; // never resolved
        events.push_back({{"name", stage_name(r.stage)},
                          {"cat", r.stage == Stage::Transfer ? "transfer" : "kernel"},
                          {"ph", "X"},
                          {"pid", pid},
                          {"tid", 1},
                          {"ts", static_cast<double>(r.start_ns - origin) * 1e-3},
                          {"dur", static_cast<double>(r.end_ns - r.start_ns) * 1e-3},
                          {"args", {{"items", r.items}}}});
    }
}

void write_trace_file(const std::filesystem::path& path, const nlohmann::json& events) {
    nlohmann::json trace = {{"traceEvents", events}, {"displayTimeUnit", "ms"}};
    std::string text = trace.dump();
    write_bytes_atomically(path, text.data(), text.size());
}

void Profiler::write_trace(const std::filesystem::path& path,
                           const std::string& device_name) const {
    nlohmann::json events = nlohmann::json::array();
    append_trace_events(events, 1, "wavepath on " + device_name);
    write_trace_file(path, events);
}

} // namespace wp
