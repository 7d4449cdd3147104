#include "cl/memory_bandwidth.hpp"

#include <algorithm>
#include <exception>
#include <map>
#include <mutex>
#include <string>

namespace wp {
namespace {

// One float4 per work-item, the widest access every device has; the launch
// is a multiple of 64 items, so there is no bounds test.
constexpr const char* kCopySource = R"(
__kernel void copy(__global const float4* source, __global float4* destination) {
    size_t i = get_global_id(0);
    destination[i] = source[i];
})";

constexpr std::size_t kBufferBytes = std::size_t{64} << 20;
constexpr int kTimedLaunches = 5; // after one untimed launch that warms up
// A first copy of this size tells how long the full measurement would take.
// Where that is more than kBudgetSeconds (a simulator such as Oclgrind takes
// minutes over 64 MiB, and it is what CI profiles on), the probe's own figure
// stands: a device that slow is bound by executing the kernel, not by its
// memory, so there is no cache effect for the large buffer to exclude.
constexpr std::size_t kProbeBytes = std::size_t{256} << 10;
constexpr double kBudgetSeconds = 2.0;

// A copy kernel and its two buffers of one size, their pages touched before
// any timing so that the figure is not page faults.
struct Copy {
    cl::Kernel kernel;
    cl::Buffer source, destination;
    std::size_t bytes;

    Copy(const DeviceContext& device, cl::CommandQueue& queue, const cl::Program& program,
         std::size_t size)
        : kernel(program, "copy"), source(device.context, CL_MEM_READ_ONLY, size),
          destination(device.context, CL_MEM_WRITE_ONLY, size), bytes(size) {
        queue.enqueueFillBuffer(source, cl_float{1.0f}, 0, bytes);
        queue.enqueueFillBuffer(destination, cl_float{0.0f}, 0, bytes);
        kernel.setArg(0, source);
        kernel.setArg(1, destination);
    }

    // Seconds one launch took on the device.
    double seconds(cl::CommandQueue& queue, const cl::NDRange& group) {
        cl::Event event;
        queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(bytes / sizeof(cl_float4)),
                                   group, nullptr, &event);
        event.wait();
        const auto start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
        const auto end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
        return end > start ? static_cast<double>(end - start) * 1e-9 : 0.0;
    }
};

double measure(const DeviceContext& device) {
    const std::size_t bytes = copy_bandwidth_buffer_bytes(device);
    cl::CommandQueue queue(device.context, device.info.device, CL_QUEUE_PROFILING_ENABLE);
    cl::Program program(device.context, std::string(kCopySource));
    program.build({device.info.device});
    const cl::NDRange group =
        device.info.max_work_group_size >= 64 ? cl::NDRange(64) : cl::NullRange;

    double probe_seconds = 0.0;
    Copy probe(device, queue, program, std::min(bytes, kProbeBytes));
    for (int launch = 0; launch < 2; ++launch) // the first launch pays for set-up
        probe_seconds = probe.seconds(queue, group);
    const double projected = probe_seconds * static_cast<double>(bytes / probe.bytes) *
                             static_cast<double>(kTimedLaunches + 1);
    if (probe_seconds > 0.0 && projected > kBudgetSeconds)
        return 2.0 * static_cast<double>(probe.bytes) / probe_seconds;

    Copy full(device, queue, program, bytes);
    double best = 0.0;
    for (int launch = 0; launch <= kTimedLaunches; ++launch) {
        const double seconds = full.seconds(queue, group);
        if (launch == 0 || seconds <= 0.0)
            continue;
        best = std::max(best, 2.0 * static_cast<double>(bytes) / seconds);
    }
    return best;
}

} // namespace

std::size_t copy_bandwidth_buffer_bytes(const DeviceContext& device) {
    const auto max_alloc = device.info.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    std::size_t bytes = std::min<std::size_t>(kBufferBytes, max_alloc);
    return bytes / (64 * sizeof(cl_float4)) * (64 * sizeof(cl_float4)); // whole work-groups
}

double measured_copy_bandwidth(const DeviceContext& device) {
    static std::mutex mutex;
    static std::map<cl_device_id, double> measured;
    std::lock_guard<std::mutex> lock(mutex);
    auto [entry, inserted] = measured.try_emplace(device.info.device(), 0.0);
    if (inserted) {
        try {
            entry->second = measure(device);
        } catch (const std::exception&) {
            entry->second = 0.0; // reported as not measured; the render itself is unaffected
        }
    }
    return entry->second;
}

} // namespace wp
