// The device buffers of one render, and the stage kernels' arguments.
//
// Both come from the buffer lists in kernels/wp_shared.h (WP_SCENE_BUFFERS,
// WP_PATH_BUFFERS), from which kernels/stage.h also generates every stage
// kernel's parameter list: (WpFrame, WpLaunch, then each buffer in list
// order). A buffer added to a list gets a member here, its allocation and its
// argument index without another line of host code (a scene buffer also
// needs the DeviceScene member of the same name that holds its contents).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "cl/cl.hpp"
#include "render/device_scene.hpp"
#include "wp_shared.h"

namespace wp {

#define WP_BUFFER_MEMBER(name, ...) cl::Buffer name;
struct DeviceBuffers {
    WP_SCENE_BUFFERS(WP_BUFFER_MEMBER)
    WP_PATH_BUFFERS(WP_BUFFER_MEMBER)
};
#undef WP_BUFFER_MEMBER

// Bytes of path buffers per path slot, per pixel, and fixed, from the list.
// Without AOVs (`aovs` false) the rows of WP_AOV_BUFFERS are one-element
// dummies, counted as fixed bytes: what allocate_device_buffers allocates.
struct PathBufferBytes {
    std::uint64_t per_slot = 0;
    std::uint64_t per_pixel = 0;
    std::uint64_t fixed = 0;
    // The largest single buffer for `slots` path slots and `pixels` pixels,
    // and its name (as in the lists of kernels/wp_shared.h).
    std::uint64_t largest(std::uint64_t slots, std::uint64_t pixels,
                          const char** name = nullptr) const;
    std::uint64_t total(std::uint64_t slots, std::uint64_t pixels) const {
        return per_slot * slots + per_pixel * pixels + fixed;
    }
};
PathBufferBytes path_buffer_bytes(bool aovs = false);

// Uploads the scene buffers (read-only) from `scene`, and allocates the path
// buffers for `slots` path slots and `pixels` pixels (contents undefined); the
// AOV rows (WP_AOV_BUFFERS) in full only with `aovs`, kernels built with
// WP_AOV being the only ones that touch them.
DeviceBuffers allocate_device_buffers(const cl::Context& context, const DeviceScene& scene,
                                      std::uint64_t slots, std::uint64_t pixels, bool aovs = false);

// The same for a prepared scene's arrays, shared by every device of a render
// (render/prepared_scene.hpp): on a `device` that shares the host's memory
// (shares_host_memory) the scene buffers are made over the arrays in place,
// not copied, and each holds `scene` until OpenCL deletes it, after the last
// command that reads it; elsewhere they are copied as above. On PoCL's CPU
// device a copy would be host memory too: a big mesh's arrays twice
// (docs/meshes.md, "The upload in place").
DeviceBuffers allocate_device_buffers(const cl::Context& context, const cl::Device& device,
                                      const std::shared_ptr<const DeviceScene>& scene,
                                      std::uint64_t slots, std::uint64_t pixels, bool aovs = false);

// Whether a buffer on `device` can use host memory at `data` as its own
// (CL_MEM_USE_HOST_PTR) without a copy: the device shares the host's memory
// (CL_DEVICE_HOST_UNIFIED_MEMORY) and `data` meets its base address
// alignment (CL_DEVICE_MEM_BASE_ADDR_ALIGN), which a DeviceArray's always does.
bool shares_host_memory(const cl::Device& device, const void* data);

// A read-only buffer holding `data`; OpenCL has no empty buffers, so an empty
// vector gets a one-element dummy.
// The data is copied once, by OpenCL, straight from `data` (a padded copy
// of a big scene's arrays would add its size to the peak host memory).
template <typename T, typename Allocator>
cl::Buffer upload_buffer(const cl::Context& context, const std::vector<T, Allocator>& data) {
    T dummy{};
    // CL_MEM_COPY_HOST_PTR only reads the pointer; the C API wants it non-const.
    void* from = data.empty() ? static_cast<void*>(&dummy)
                              : const_cast<void*>(static_cast<const void*>(data.data()));
    return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                      sizeof(T) * std::max<std::size_t>(data.size(), 1), from);
}

// Argument indices of every stage kernel.
inline constexpr cl_uint kFrameArgument = 0;
inline constexpr cl_uint kLaunchArgument = 1;

// Binds every buffer to its argument of a stage kernel (once per kernel; the
// frame and launch arguments are set per launch).
void bind_buffers(cl::Kernel& kernel, const DeviceBuffers& buffers);

// Binds the scene buffers, in list order, to arguments first, first + 1, ...
// of a kernel declared with WP_SCENE_BUFFERS(WP_SCENE_PARAMETER) there (test
// kernels); returns the index after them.
cl_uint bind_scene_buffers(cl::Kernel& kernel, cl_uint first, const DeviceBuffers& buffers);

// A launch of one stage: what goes in WpLaunch.
WpLaunch make_launch(std::uint32_t count, std::uint32_t ray_queue, bool from_finished = false,
                     bool sorted = false);

} // namespace wp
