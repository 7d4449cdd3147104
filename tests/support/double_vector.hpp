// The double-precision 3-vector of the host reference models (kernel stage
// tests, stability tests): glm::dvec3, with the conversions to and from the
// kernels' float4. dot, cross, length, normalize and distance are GLM's.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cl/cl.hpp"
#include "render/device_scene.hpp"

namespace wp::test {

// The short name keeps the reference formulas, which use it on almost every
// line, readable. Note that a default-constructed glm::dvec3 is not zeroed.
using D3 = glm::dvec3;

inline D3 from_float4(const cl_float4& v) {
    return {v.s[0], v.s[1], v.s[2]};
}

// Corner i (0, 1 or 2) of a device triangle, in double.
inline D3 triangle_vertex(const WpTriangle& t, int i) {
    return from_float4(i == 0 ? t.v0 : (i == 1 ? t.v1 : t.v2));
}

// The renderer's own conversion (render/device_scene.hpp).
using wp::to_float4;

// The value a double vector takes once rounded to float, back in double.
inline D3 rounded(const D3& v) {
    return from_float4(to_float4(v));
}

inline double max_abs(const D3& v) {
    return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z)));
}

} // namespace wp::test
