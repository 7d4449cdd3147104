// The headers nearly every test file includes, parsed once per test program
// rather than once per file (CMakeLists.txt, WAVEPATH_PRECOMPILED_HEADERS):
// Catch2's single header, the OpenCL C++ bindings and the standard library
// headers cost more to parse than most tests take to compile. Each test file
// still includes what it uses, so it builds the same without them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

// Only in the programs that link the OpenCL layer, which configures the bindings.
#ifdef CL_HPP_TARGET_OPENCL_VERSION
#include "cl/cl.hpp"
#endif
