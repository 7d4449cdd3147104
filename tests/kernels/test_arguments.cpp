// Every stage kernel takes exactly (frame, launch, then every buffer of the
// lists in kernels/wp_shared.h, in order), by the names the lists give: the
// host binds by the same lists (src/render/device_buffers.cpp), so an
// argument cannot shift. Read back from the compiled kernels with
// -cl-kernel-arg-info, independently of the macros that declare them.
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "cl/stages.hpp"

using namespace wp;
using namespace wp::test;

namespace {

std::vector<std::string> expected_parameters() {
    std::vector<std::string> names = {"frame", "launch"};
#define WP_NAME(name, ...) names.push_back(#name);
    WP_SCENE_BUFFERS(WP_NAME)
    WP_PATH_BUFFERS(WP_NAME)
#undef WP_NAME
    return names;
}

} // namespace

TEST_CASE("stage kernels: every stage takes the frame, the launch and every listed buffer, in "
          "list order and by name",
          "[cl][arguments]") {
    BuiltProgram built = build_wavefront_program(device().context, device().info.device,
                                                 "-cl-kernel-arg-info", CachePolicy::off());
    const std::vector<std::string> expected = expected_parameters();
    REQUIRE(expected.size() > 20);
    for (std::string_view stage : kStageKernelNames) {
        INFO(stage);
        cl::Kernel kernel(built.program, std::string(stage).c_str());
        const cl_uint count = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
        REQUIRE(count == expected.size());
        for (cl_uint i = 0; i < count; ++i) {
            std::string name = kernel.getArgInfo<CL_KERNEL_ARG_NAME>(i);
            name.erase(name.find_last_not_of('\0') + 1); // some drivers count the terminator
            CHECK(name == expected[i]);
            const cl_kernel_arg_address_qualifier space =
                kernel.getArgInfo<CL_KERNEL_ARG_ADDRESS_QUALIFIER>(i);
            CHECK(space == (i < 2 ? CL_KERNEL_ARG_ADDRESS_PRIVATE : CL_KERNEL_ARG_ADDRESS_GLOBAL));
        }
        CHECK(kernel.getArgInfo<CL_KERNEL_ARG_TYPE_NAME>(0).find("WpFrame") != std::string::npos);
        CHECK(kernel.getArgInfo<CL_KERNEL_ARG_TYPE_NAME>(1).find("WpLaunch") != std::string::npos);
    }
}

TEST_CASE("stage kernels: the host binds one buffer per listed name, and sizes them from the "
          "lists",
          "[cl][arguments]") {
    // Path buffers of 3 slots and 5 pixels: sizes straight from the lists.
    DeviceBuffers buffers = stage_buffers(3, 5);
    CHECK(buffers.ray_queues.getInfo<CL_MEM_SIZE>() == 2 * 3 * sizeof(cl_uint));
    CHECK(buffers.ray_origin.getInfo<CL_MEM_SIZE>() == 3 * sizeof(cl_float4));
    CHECK(buffers.film_sum.getInfo<CL_MEM_SIZE>() == 5 * sizeof(cl_float4));
    CHECK(buffers.counters.getInfo<CL_MEM_SIZE>() == WP_COUNTER_COUNT * sizeof(cl_uint));
    // The memory check's totals agree with the buffers allocated.
    std::uint64_t total = 0;
#define WP_SIZE(name, ...) total += buffers.name.getInfo<CL_MEM_SIZE>();
    WP_PATH_BUFFERS(WP_SIZE)
#undef WP_SIZE
    CHECK(path_buffer_bytes().total(3, 5) == total);
    const char* name = nullptr;
    // (16 pixels and 16 slots: with 8 or fewer, the fixed 128 bytes of
    // tail_lengths would be largest)
    CHECK(path_buffer_bytes().largest(3, 16, &name) == 16 * sizeof(cl_float4)); // a film buffer
    CHECK(std::string(name) == "film_sum");
    CHECK(path_buffer_bytes().largest(16, 1, &name) == 16 * sizeof(cl_float4)); // a path buffer
    CHECK(std::string(name) == "ray_origin");
}

TEST_CASE("stage kernels: the AOV buffers are rows of the path list, allocated per pixel only "
          "for a render with AOVs",
          "[cl][arguments]") {
    std::vector<std::string> aov_rows;
#define WP_AOV_NAME(name, ...) aov_rows.push_back(#name);
    WP_AOV_BUFFERS(WP_AOV_NAME)
#undef WP_AOV_NAME
    CHECK(aov_rows == std::vector<std::string>{"aov_albedo", "aov_normal", "aov_depth"});
    const std::vector<std::string> all = expected_parameters();
    CHECK(std::equal(aov_rows.rbegin(), aov_rows.rend(), all.rbegin())); // the list's last rows

    const DeviceBuffers without = stage_buffers(3, 5);
    CHECK(without.aov_albedo.getInfo<CL_MEM_SIZE>() == sizeof(cl_float4)); // a dummy
    CHECK(without.aov_depth.getInfo<CL_MEM_SIZE>() == sizeof(cl_float));
    const DeviceBuffers with =
        allocate_device_buffers(device().context, DeviceScene{}, 3, 5, /*aovs=*/true);
    CHECK(with.aov_albedo.getInfo<CL_MEM_SIZE>() == 5 * sizeof(cl_float4));
    CHECK(with.aov_normal.getInfo<CL_MEM_SIZE>() == 5 * sizeof(cl_float4));
    CHECK(with.aov_depth.getInfo<CL_MEM_SIZE>() == 5 * sizeof(cl_float));
    std::uint64_t total = 0;
#define WP_SIZE(name, ...) total += with.name.getInfo<CL_MEM_SIZE>();
    WP_PATH_BUFFERS(WP_SIZE)
#undef WP_SIZE
    CHECK(path_buffer_bytes(true).total(3, 5) == total);
    CHECK(path_buffer_bytes(true).per_pixel ==
          path_buffer_bytes(false).per_pixel + 2 * sizeof(cl_float4) + sizeof(cl_float));
}
