// One OpenCL device with its own context and in-order command queue.
//
// Everything that renders holds one of these per device, so that a render can
// span several devices by giving each its own context, programs, buffers and
// film (render/multi_device.hpp, docs/multi-device.md).
#pragma once

#include "cl/cl.hpp"
#include "cl/device.hpp"

namespace wp {

struct DeviceContext {
    DeviceInfo info;
    cl::Context context;
    cl::CommandQueue queue;

    explicit DeviceContext(DeviceInfo device, bool profiling = false)
        : info(std::move(device)), context(info.device),
          queue(context, info.device, profiling ? CL_QUEUE_PROFILING_ENABLE : 0) {}
};

} // namespace wp
