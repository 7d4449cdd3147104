#include "cl/error.hpp"

namespace wp {

const char* cl_error_name(cl_int code) {
    switch (code) {
#define WP_CASE(name)                                                                              \
    case name:                                                                                     \
        return #name
        WP_CASE(CL_SUCCESS);
        WP_CASE(CL_DEVICE_NOT_FOUND);
        WP_CASE(CL_DEVICE_NOT_AVAILABLE);
        WP_CASE(CL_COMPILER_NOT_AVAILABLE);
        WP_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE);
        WP_CASE(CL_OUT_OF_RESOURCES);
        WP_CASE(CL_OUT_OF_HOST_MEMORY);
        WP_CASE(CL_PROFILING_INFO_NOT_AVAILABLE);
        WP_CASE(CL_BUILD_PROGRAM_FAILURE);
        WP_CASE(CL_INVALID_VALUE);
        WP_CASE(CL_INVALID_DEVICE);
        WP_CASE(CL_INVALID_CONTEXT);
        WP_CASE(CL_INVALID_COMMAND_QUEUE);
        WP_CASE(CL_INVALID_MEM_OBJECT);
        WP_CASE(CL_INVALID_BINARY);
        WP_CASE(CL_INVALID_BUILD_OPTIONS);
        WP_CASE(CL_INVALID_PROGRAM);
        WP_CASE(CL_INVALID_PROGRAM_EXECUTABLE);
        WP_CASE(CL_INVALID_KERNEL_NAME);
        WP_CASE(CL_INVALID_KERNEL);
        WP_CASE(CL_INVALID_ARG_INDEX);
        WP_CASE(CL_INVALID_ARG_VALUE);
        WP_CASE(CL_INVALID_ARG_SIZE);
        WP_CASE(CL_INVALID_KERNEL_ARGS);
        WP_CASE(CL_INVALID_WORK_DIMENSION);
        WP_CASE(CL_INVALID_WORK_GROUP_SIZE);
        WP_CASE(CL_INVALID_WORK_ITEM_SIZE);
        WP_CASE(CL_INVALID_GLOBAL_OFFSET);
        WP_CASE(CL_INVALID_EVENT);
        WP_CASE(CL_INVALID_OPERATION);
        WP_CASE(CL_INVALID_BUFFER_SIZE);
        WP_CASE(CL_INVALID_GLOBAL_WORK_SIZE);
#undef WP_CASE
    case -1001:
        return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
        return "unknown OpenCL error";
    }
}

std::string describe_cl_error(const cl::Error& error) {
    std::string text = std::string(error.what()) + " failed: " + cl_error_name(error.err()) + " (" +
                       std::to_string(error.err()) + ")";
    switch (error.err()) {
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
    case CL_OUT_OF_HOST_MEMORY:
        return text + ": out of device memory; try a smaller --width/--height";
    case CL_OUT_OF_RESOURCES:
        return text + ": the device ran out of resources (memory or a kernel fault)";
    case CL_INVALID_BUFFER_SIZE:
        return text + ": a buffer is larger than the device allows; try a smaller image";
    default:
        return text;
    }
}

} // namespace wp
