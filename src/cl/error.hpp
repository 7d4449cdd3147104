// Turning OpenCL error codes into sentences a user can act on.
#pragma once

#include <string>

#include "cl/cl.hpp"

namespace wp {

// The symbolic name of an OpenCL error code, e.g. "CL_OUT_OF_RESOURCES".
const char* cl_error_name(cl_int code);

// One line: the failing call, the code's name, and what it usually means,
// e.g. "clCreateBuffer failed: CL_MEM_OBJECT_ALLOCATION_FAILURE (out of device memory)".
std::string describe_cl_error(const cl::Error& error);

} // namespace wp
