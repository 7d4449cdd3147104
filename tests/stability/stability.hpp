// Shared helpers of the stability suite (docs/stability.md): loading the stress
// scenes, comparing renders within noise, small OpenCL test kernels that call
// the intersection code of kernels/triangle.h, sphere.h and traverse.h directly,
// and double-precision reference intersections.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cl/cl.hpp"
#include "cl/program.hpp"
#include "naive.hpp"
#include "scene/load.hpp"
#include "support/double_vector.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"
#include "support/test_device.hpp"
#include "wp_shared.h"

namespace wp::stability {

// "Within noise" (specs/stability.md): under five standard errors.
constexpr double kSigmas = 5.0;

inline std::string stress_path(const std::string& name) {
    return std::string(WAVEPATH_SOURCE_DIR) + "/scenes/stress/" + name + ".json";
}

inline Scene stress_scene(const std::string& name, int width = 0, int height = 0) {
    Scene scene = load_scene(stress_path(name));
    if (width > 0) {
        scene.camera.width = width;
        scene.camera.height = height > 0 ? height : width;
    }
    return scene;
}

inline Scene hexroom(int size) {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
    scene.camera.width = size;
    scene.camera.height = size;
    return scene;
}

// Every point mapped to s * p + offset, every radius times s; the camera too.
inline Scene transformed(Scene scene, double s, glm::dvec3 offset = glm::dvec3(0.0)) {
    scene.camera.eye = s * scene.camera.eye + offset;
    scene.camera.look_at = s * scene.camera.look_at + offset;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        Triangle t = scene.triangles[i];
        for (glm::dvec3& v : t.v)
            v = s * v + offset;
        scene.triangles.set(i, t);
    }
    for (Sphere& sp : scene.spheres) {
        sp.center = s * sp.center + offset;
        sp.radius *= s;
    }
    return scene;
}

inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every value of the estimate is finite (and the film saw no non-finite sample).
inline bool all_finite(const test::Rendered& r) {
    Image mean = r.film.mean();
    Image variance = r.film.variance_of_mean();
    for (std::size_t i = 0; i < mean.rgb.size(); ++i)
        if (!std::isfinite(mean.rgb[i]) || !std::isfinite(variance.rgb[i]))
            return false;
    return r.stats.nonfinite_samples == 0;
}

// Shared with the render tests (support/render_helpers.hpp).
using test::BlockComparison;
using test::compare_blocks;
using test::region_mean;

// Whole-image mean per channel, difference in combined standard errors.
inline double image_mean_sigmas(const Film& a, const Film& b, int channel) {
    test::MeanWithError ma = test::image_mean(a, channel), mb = test::image_mean(b, channel);
    return std::abs(ma.mean - mb.mean) / std::hypot(ma.standard_error, mb.standard_error);
}

// ---------------------------------------------------------------- OpenCL

// Builds a test kernel's source (which may include the embedded kernel
// headers, e.g. "traverse.h") once per executable and option string.
inline const cl::Program& test_program(const std::string& source, const std::string& name,
                                       const std::string& options = "") {
    static auto& cache = *new std::map<std::string, cl::Program>; // never released
    const std::string key = name + '\n' + options + '\n' + source;
    auto found = cache.find(key);
    if (found != cache.end())
        return found->second;
    try {
        BuiltProgram built = build_program(test::device().context, test::device().info.device,
                                           source, name, options);
        return cache.emplace(key, built.program).first->second;
    } catch (const BuildError& error) {
        FAIL(error.what() << '\n' << error.log());
        throw;
    }
}

template <typename T> cl::Buffer upload(const std::vector<T>& data) {
    std::vector<T> padded = data.empty() ? std::vector<T>(1) : data;
    return cl::Buffer(test::device().context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      sizeof(T) * padded.size(), padded.data());
}

template <typename T> std::vector<T> download(const cl::Buffer& buffer, std::size_t count) {
    std::vector<T> out(count);
    if (count > 0)
        test::device().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, sizeof(T) * count, out.data());
    return out;
}

constexpr std::size_t kLocalSize = 64;

inline void launch(cl::Kernel& kernel, std::size_t items) {
    std::size_t global =
        std::max<std::size_t>(1, (items + kLocalSize - 1) / kLocalSize) * kLocalSize;
    test::device().queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global),
                                              cl::NDRange(kLocalSize));
    test::device().queue.finish();
}

template <typename... Args> void set_args(cl::Kernel& kernel, const Args&... args) {
    cl_uint index = 0;
    (kernel.setArg(index++, args), ...);
}

// ---------------------------------------------------------------- double references

using test::D3;
using test::from_float4;
using test::max_abs;
using test::rounded;
using test::to_float4;

// Ray/triangle in double, both faces: the ray parameter t where the line
// meets the plane, and the barycentric coordinates (b0, b1, b2) of that point
// (the triangle holds it when all three are >= 0). Returns false for a ray
// parallel to the plane.
struct PlaneHit {
    double t = 0.0;
    double b[3] = {0.0, 0.0, 0.0};
    double min_barycentric() const { return std::min(b[0], std::min(b[1], b[2])); }
};

inline bool plane_hit(const D3& o, const D3& d, const D3& v0, const D3& v1, const D3& v2,
                      PlaneHit* out) {
    // long double: the references must be far more precise than float, and
    // grazing rays stress even double's cancellation.
    using L = long double;
    L e1[3] = {L(v1.x) - v0.x, L(v1.y) - v0.y, L(v1.z) - v0.z};
    L e2[3] = {L(v2.x) - v0.x, L(v2.y) - v0.y, L(v2.z) - v0.z};
    L n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
              e1[0] * e2[1] - e1[1] * e2[0]};
    L dn = n[0] * d.x + n[1] * d.y + n[2] * d.z;
    if (dn == 0)
        return false;
    L w[3] = {L(v0.x) - o.x, L(v0.y) - o.y, L(v0.z) - o.z};
    L t = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / dn;
    L p[3] = {L(o.x) + t * d.x - v0.x, L(o.y) + t * d.y - v0.y, L(o.z) + t * d.z - v0.z};
    // Barycentrics of p (relative to v0) from the areas of the sub-triangles.
    auto area = [&](const L* a, const L* b) {
        L c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        return c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
    };
    L nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    L b1 = area(p, e2) / nn; // weight of v1
    L b2 = area(e1, p) / nn; // weight of v2
    out->t = static_cast<double>(t);
    out->b[1] = static_cast<double>(b1);
    out->b[2] = static_cast<double>(b2);
    out->b[0] = static_cast<double>(1 - b1 - b2);
    return true;
}

// Ray/sphere in long double: the nearest root with t > 0, or -1.
inline double sphere_hit(const D3& o, const D3& d, const D3& c, double r) {
    using L = long double;
    L f[3] = {L(o.x) - c.x, L(o.y) - c.y, L(o.z) - c.z};
    L a = L(d.x) * d.x + L(d.y) * d.y + L(d.z) * d.z;
    L hb = f[0] * d.x + f[1] * d.y + f[2] * d.z;
    L cc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - L(r) * r;
    L disc = hb * hb - a * cc;
    if (disc < 0)
        return -1.0;
    L q = -(hb + (hb < 0 ? -1 : 1) * std::sqrt(disc));
    L t0 = cc / q, t1 = q / a;
    if (t0 > t1)
        std::swap(t0, t1);
    if (t0 > 0)
        return static_cast<double>(t0);
    return t1 > 0 ? static_cast<double>(t1) : -1.0;
}

// ---------------------------------------------------------------- the trace kernel

// Closest hits of a list of rays against triangles and spheres, through
// wp_closest_hit of kernels/traverse.h exactly as the intersect stage calls
// it, or (-D ST_NAIVE=1) through the naive tests of naive.hpp.
inline const std::string kTraceSource = std::string(kNaiveTraversalSource) + R"CLC(
__kernel void trace(wp_uint count, __global const float4* origins,
                    __global const float4* directions, __global const WpTriangle* triangles,
                    wp_uint triangle_count, __global const WpSphere* spheres,
                    wp_uint sphere_count, __global float* t_out, __global wp_uint* hit_out) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    WpSceneView scene = st_scene_view(triangles, triangle_count, spheres, sphere_count);
    float t;
    hit_out[i] = st_closest_hit(&scene, origins[i].xyz, directions[i].xyz, INFINITY, &t);
    t_out[i] = t;
}
)CLC";

struct TraceResult {
    std::vector<float> t;
    std::vector<cl_uint> hit;
};

inline TraceResult trace(const std::vector<cl_float4>& origins,
                         const std::vector<cl_float4>& directions,
                         const std::vector<WpTriangle>& triangles,
                         const std::vector<WpSphere>& spheres, bool naive) {
    const cl::Program& program =
        test_program(kTraceSource, "stability_trace.cl", naive ? "-D ST_NAIVE=1" : "");
    cl::Kernel kernel(program, "trace");
    const std::size_t n = origins.size();
    cl::Buffer o = upload(origins), d = upload(directions), tri = upload(triangles),
               sph = upload(spheres);
    cl::Buffer t(test::device().context, CL_MEM_READ_WRITE,
                 sizeof(float) * std::max<std::size_t>(n, 1));
    cl::Buffer h(test::device().context, CL_MEM_READ_WRITE,
                 sizeof(cl_uint) * std::max<std::size_t>(n, 1));
    set_args(kernel, static_cast<cl_uint>(n), o, d, tri, static_cast<cl_uint>(triangles.size()),
             sph, static_cast<cl_uint>(spheres.size()), t, h);
    launch(kernel, n);
    return {download<float>(t, n), download<cl_uint>(h, n)};
}

inline WpTriangle make_triangle(const D3& a, const D3& b, const D3& c, cl_uint material = 0) {
    WpTriangle t{};
    t.v0 = to_float4(a);
    t.v1 = to_float4(b);
    t.v2 = to_float4(c);
    wp_set_triangle_material(&t, material);
    return t;
}

inline WpSphere make_sphere(const D3& centre, double radius, cl_uint material = 0) {
    WpSphere s{};
    s.center_radius = to_float4(centre, radius);
    s.material = material;
    return s;
}

} // namespace wp::stability
