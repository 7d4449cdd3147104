// wavepath_oclgrind_probe: kernels with one deliberate fault each, built only
// for the test of the Oclgrind step's detector (tools/oclgrind-run). Every
// mode runs and exits 0 on any device; only a checking device notices.
//
//   clean       every work-item writes its own element (nothing to report)
//   global-oob  one work-item writes one element past the end of a buffer
//   local-oob   one work-item writes one element past a __local array
//   race        every work-item writes a different value to one element
//   api         an enqueue with a local size that does not divide the global
//               size (CL_INVALID_WORK_GROUP_SIZE), caught and ignored
//
// The device is WAVEPATH_TEST_DEVICE's, else the default one.
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "cl/cl.hpp"
#include "cl/context.hpp"
#include "cl/device.hpp"

namespace {

const char* kSource = R"CL(
__kernel void wp_probe_clean(__global uint* out, uint n) {
    uint i = get_global_id(0);
    if (i < n)
        out[i] = i;
}

__kernel void wp_probe_global_oob(__global uint* out, uint n) {
    uint i = get_global_id(0);
    if (i <= n) /* should be i < n: item n writes out[n], one past the end */
        out[i] = i;
}

__kernel void wp_probe_local_oob(__global uint* out, uint n) {
    __local uint tile[16];
    uint l = get_local_id(0);
    tile[l + 1] = l; /* should be tile[l]: item 15 writes tile[16] */
    barrier(CLK_LOCAL_MEM_FENCE);
    uint i = get_global_id(0);
    if (i < n && l + 1 < 16)
        out[i] = tile[l + 1];
}

__kernel void wp_probe_race(__global uint* out, uint n) {
    uint i = get_global_id(0);
    if (i < n)
        out[0] = i; /* every item stores a different value to one element, unsynchronised */
}
)CL";

constexpr cl_uint kItems = 64;                   // elements of the output buffer
constexpr std::size_t kGroup = 16;               // work-group size
constexpr std::size_t kLaunch = kItems + kGroup; // one group more than there are elements

} // namespace

int main(int argc, char** argv) {
    const std::string mode = argc == 2 ? argv[1] : "";
    const char* kernel_name = mode == "global-oob"               ? "wp_probe_global_oob"
                              : mode == "local-oob"              ? "wp_probe_local_oob"
                              : mode == "race"                   ? "wp_probe_race"
                              : mode == "clean" || mode == "api" ? "wp_probe_clean"
                                                                 : nullptr;
    if (!kernel_name) {
        std::cerr << "usage: wavepath_oclgrind_probe clean|global-oob|local-oob|race|api\n";
        return 2;
    }
    try {
        const char* selector = std::getenv("WAVEPATH_TEST_DEVICE");
        wp::DeviceContext device(wp::select_device(selector ? selector : ""));
        cl::Program program(device.context, kSource);
        program.build({device.info.device});
        cl::Kernel kernel(program, kernel_name);
        // The buffer wraps host memory with one spare element after its end, so
        // that on a CPU device that does not check (PoCL uses the host memory
        // itself) the out-of-bounds write lands there and corrupts nothing.
        std::vector<cl_uint> host(kItems + 1, 0);
        cl::Buffer out(device.context, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR,
                       kItems * sizeof(cl_uint), host.data());
        kernel.setArg(0, out);
        kernel.setArg(1, kItems);
        if (mode == "api") {
            try {
                device.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(kLaunch - 1),
                                                  cl::NDRange(kGroup));
                std::cerr << "wavepath_oclgrind_probe: the invalid enqueue was accepted\n";
            } catch (const cl::Error& e) {
                std::cout << "the invalid enqueue failed as it should (" << e.err() << ")\n";
            }
        }
        device.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(kLaunch),
                                          cl::NDRange(kGroup));
        std::vector<cl_uint> result(kItems);
        device.queue.enqueueReadBuffer(out, CL_TRUE, 0, kItems * sizeof(cl_uint), result.data());
        std::cout << "wavepath_oclgrind_probe " << mode << ": ran on " << device.info.name << "\n";
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "wavepath_oclgrind_probe: error: " << e.what() << "\n";
        return 1;
    }
}
