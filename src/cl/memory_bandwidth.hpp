// The device's measured memory bandwidth: what a plain copy kernel moves per
// second. The profile divides each stage's bytes by its time and compares
// the result with this figure (docs/profiling.md, "Speed of light").
#pragma once

#include <cstddef>

#include "cl/context.hpp"

namespace wp {

// Bytes read plus bytes written per second by a kernel that copies a buffer
// much larger than the caches (float4 per work-item), best of a few timed
// launches on a queue of its own. Measured once per device and process (the
// first call takes a kernel build and a fraction of a second), then cached;
// 0 where the measurement failed. On a device so slow that the full copy would
// take seconds (a simulator), a 256 KiB copy's figure instead.
double measured_copy_bandwidth(const DeviceContext& device);

// The buffer size the copy uses on `device`: 64 MiB each way, or less where
// the device's largest allocation is smaller.
std::size_t copy_bandwidth_buffer_bytes(const DeviceContext& device);

} // namespace wp
