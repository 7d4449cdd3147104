// The Khronos C++ bindings, configured for OpenCL 1.2 with exceptions.
// Include this instead of <CL/opencl.hpp> so every file agrees on the settings.
#pragma once

#include <CL/opencl.hpp>
