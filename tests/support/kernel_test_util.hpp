// Helpers for the kernel-level tests: buffers to and from the shared test
// device, launches with a fixed work-group size, and the programs under test.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "cl/cl.hpp"
#include "cl/program.hpp"
#include "render/device_buffers.hpp"
#include "support/double_vector.hpp"
#include "support/test_device.hpp"
#include "wp_shared.h"

#include <catch2/catch.hpp>

namespace wp::test {

// Every launch uses this work-group size (PoCL compiles a kernel anew for each
// distinct local size) and rounds the item count up to a multiple of it, so the
// kernels' guards against excess work-items are exercised too.
constexpr std::size_t kLocalSize = 64;

inline std::size_t round_up(std::size_t items) {
    return std::max<std::size_t>(1, (items + kLocalSize - 1) / kLocalSize) * kLocalSize;
}

// A read-write buffer holding a copy of `data` (at least one element).
template <typename T, typename Allocator> cl::Buffer upload(const std::vector<T, Allocator>& data) {
    std::vector<T> padded =
        data.empty() ? std::vector<T>(1) : std::vector<T>(data.begin(), data.end());
    return cl::Buffer(device().context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      sizeof(T) * padded.size(), padded.data());
}

// The first `count` elements of `buffer`.
template <typename T> std::vector<T> download(const cl::Buffer& buffer, std::size_t count) {
    std::vector<T> out(count);
    if (count > 0)
        device().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, sizeof(T) * count, out.data());
    return out;
}

// Runs `kernel` over `items` work-items (global size rounded up to a multiple
// of kLocalSize) and waits for it.
inline void launch(cl::Kernel& kernel, std::size_t items) {
    device().queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(round_up(items)),
                                        cl::NDRange(kLocalSize));
    device().queue.finish();
}

// Sets kernel arguments 0, 1, 2, ... in order.
template <typename... Args> void set_args(cl::Kernel& kernel, const Args&... args) {
    cl_uint index = 0;
    (kernel.setArg(index++, args), ...);
}

// Builds test-kernel source (which may include the embedded kernel headers)
// once per executable; a failed build reports the compiler log.
inline const cl::Program& program(const std::string& source, const std::string& name,
                                  const std::string& options = "") {
    static auto& cache = *new std::map<std::string, cl::Program>; // never released
    std::string key = name + '\n' + options + '\n' + source;
    auto found = cache.find(key);
    if (found != cache.end())
        return found->second;
    try {
        BuiltProgram built =
            build_program(device().context, device().info.device, source, name, options);
        return cache.emplace(key, built.program).first->second;
    } catch (const BuildError& error) {
        FAIL(error.what() << '\n' << error.log());
        throw;
    }
}

// The five wavefront stages with every feature compiled in, built once per
// set of extra build options (say "-D WP_TRIANGLE_COUNT=2 -D WP_SPHERE_COUNT=1",
// the fixed-count specialisation that PoCL vectorises).
inline const cl::Program& wavefront_program(const std::string& options = "") {
    static auto& cache = *new std::map<std::string, cl::Program>; // never released
    auto found = cache.find(options);
    if (found == cache.end())
        found = cache
                    .emplace(options, build_wavefront_program(device().context,
                                                              device().info.device, options)
                                          .program)
                    .first;
    return found->second;
}

inline cl::Kernel wavefront_kernel(const char* name, const std::string& options = "") {
    return cl::Kernel(wavefront_program(options), name);
}

// Every buffer a stage kernel takes, for `slots` path slots and `pixels`
// pixels, with an empty scene; contents undefined. A test replaces the
// buffers it fills or reads (members named as in kernels/wp_shared.h).
inline DeviceBuffers stage_buffers(std::size_t slots, std::size_t pixels) {
    return allocate_device_buffers(device().context, DeviceScene{}, slots, pixels);
}

// Runs stage `name` with `frame` and `arguments` over `items` work-items,
// bound to `buffers` exactly as the integrator binds them.
inline void run_stage(const char* name, const WpFrame& frame, const WpLaunch& arguments,
                      const DeviceBuffers& buffers, std::size_t items,
                      const std::string& options = "") {
    cl::Kernel kernel = wavefront_kernel(name, options);
    bind_buffers(kernel, buffers);
    kernel.setArg(kFrameArgument, frame);
    kernel.setArg(kLaunchArgument, arguments);
    launch(kernel, items);
}

inline cl_float4 float4(float x, float y, float z, float w = 0.0f) {
    cl_float4 v;
    v.s[0] = x;
    v.s[1] = y;
    v.s[2] = z;
    v.s[3] = w;
    return v;
}

inline std::uint32_t float_bits(float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits;
}

// One (pixel, sample) pair a path slot computes.
struct Task {
    cl_uint pixel = 0, sample = 0;

    bool operator==(const Task& o) const { return pixel == o.pixel && sample == o.sample; }
    bool operator<(const Task& o) const {
        return pixel != o.pixel ? pixel < o.pixel : sample < o.sample;
    }
};

// The tasks of path slot `slot`, in the order generate must hand them out,
// built from the description in wp_shared.h rather than from generate's
// arithmetic: the slot owns pixels slot, slot + pool_size, ... below
// width x height, and works through samples first_sample, first_sample + 1,
// ... one at a time, each for all its pixels in turn (sample-major).
inline std::vector<Task> slot_tasks(const WpFrame& frame, cl_uint slot) {
    const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
    std::vector<Task> out;
    for (cl_uint s = 0; s < frame.sample_count; ++s)
        for (std::uint64_t pixel = slot; pixel < pixels; pixel += frame.pool_size)
            out.push_back({cl_uint(pixel), frame.first_sample + s});
    return out;
}

} // namespace wp::test
