// The structs of wp_shared.h have the same layout on the device as on the host,
// a WpFrame passed by value arrives field for field, and the RNG of rng.h gives
// the same bits on both sides.
#include "render/device_scene.hpp"
#include "rng.h"
#include "support/kernel_test_util.hpp"

#include <cmath>
#include <cstddef>
#include <iterator>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace wp::test;

namespace {

// Every struct of wp_shared.h, and every field of each.
#define WP_LAYOUT_STRUCTS(X)                                                                       \
    X(WpTriangle)                                                                                  \
    X(WpShadingNormals)                                                                            \
    X(WpSphere)                                                                                    \
    X(WpTriangleUvs)                                                                               \
    X(WpTexture)                                                                                   \
    X(WpMaterial)                                                                                  \
    X(WpLight)                                                                                     \
    X(WpEmitter) X(WpMirrorGroup) X(WpBvhNode) X(WpInstance) X(WpCamera) X(WpFrame) X(WpLaunch)

#define WP_LAYOUT_FIELDS(X)                                                                        \
    X(WpTriangle, v0)                                                                              \
    X(WpTriangle, v1)                                                                              \
    X(WpTriangle, v2)                                                                              \
    X(WpShadingNormals, n0)                                                                        \
    X(WpShadingNormals, n1)                                                                        \
    X(WpShadingNormals, n2)                                                                        \
    X(WpSphere, center_radius)                                                                     \
    X(WpSphere, material)                                                                          \
    X(WpSphere, pad0)                                                                              \
    X(WpSphere, pad1)                                                                              \
    X(WpSphere, pad2)                                                                              \
    X(WpMaterial, reflectance)                                                                     \
    X(WpMaterial, emission)                                                                        \
    X(WpMaterial, eta)                                                                             \
    X(WpMaterial, k)                                                                               \
    X(WpMaterial, transmittance)                                                                   \
    X(WpMaterial, specular)                                                                        \
    X(WpMaterial, kind)                                                                            \
    X(WpMaterial, distribution)                                                                    \
    X(WpMaterial, fresnel)                                                                         \
    X(WpMaterial, alpha_u)                                                                         \
    X(WpMaterial, alpha_v)                                                                         \
    X(WpMaterial, fdr_int)                                                                         \
    X(WpMaterial, specular_weight)                                                                 \
    X(WpMaterial, nonlinear)                                                                       \
    X(WpMaterial, reflectance_texture)                                                             \
    X(WpMaterial, specular_texture)                                                                \
    X(WpMaterial, transmittance_texture)                                                           \
    X(WpMaterial, alpha_u_texture)                                                                 \
    X(WpMaterial, alpha_v_texture)                                                                 \
    X(WpMaterial, pad0)                                                                            \
    X(WpMaterial, pad1)                                                                            \
    X(WpMaterial, pad2)                                                                            \
    X(WpTriangleUvs, u)                                                                            \
    X(WpTriangleUvs, v)                                                                            \
    X(WpTexture, color0)                                                                           \
    X(WpTexture, color1)                                                                           \
    X(WpTexture, to_u)                                                                             \
    X(WpTexture, to_v)                                                                             \
    X(WpTexture, kind)                                                                             \
    X(WpTexture, format)                                                                           \
    X(WpTexture, width)                                                                            \
    X(WpTexture, height)                                                                           \
    X(WpTexture, first)                                                                            \
    X(WpTexture, wrap)                                                                             \
    X(WpTexture, filter)                                                                           \
    X(WpTexture, pad0)                                                                             \
    X(WpMaterial, rough_transmittance)                                                             \
    X(WpBvhNode, lower_x)                                                                          \
    X(WpBvhNode, upper_x)                                                                          \
    X(WpBvhNode, lower_y)                                                                          \
    X(WpBvhNode, upper_y)                                                                          \
    X(WpBvhNode, lower_z)                                                                          \
    X(WpBvhNode, upper_z)                                                                          \
    X(WpBvhNode, child)                                                                            \
    X(WpBvhNode, count)                                                                            \
    X(WpLight, triangle)                                                                           \
    X(WpLight, cdf)                                                                                \
    X(WpLight, guide)                                                                              \
    X(WpLight, pad0)                                                                               \
    X(WpEmitter, position)                                                                         \
    X(WpEmitter, direction)                                                                        \
    X(WpEmitter, radiance)                                                                         \
    X(WpEmitter, kind)                                                                             \
    X(WpEmitter, pick)                                                                             \
    X(WpEmitter, cdf)                                                                              \
    X(WpEmitter, reach)                                                                            \
    X(WpEmitter, cos_cutoff)                                                                       \
    X(WpEmitter, cos_beam)                                                                         \
    X(WpEmitter, cutoff)                                                                           \
    X(WpEmitter, inv_transition)                                                                   \
    X(WpMirrorGroup, plane)                                                                        \
    X(WpMirrorGroup, first)                                                                        \
    X(WpMirrorGroup, count)                                                                        \
    X(WpMirrorGroup, pad0)                                                                         \
    X(WpMirrorGroup, pad1)                                                                         \
    X(WpCamera, eye)                                                                               \
    X(WpCamera, forward)                                                                           \
    X(WpCamera, right)                                                                             \
    X(WpCamera, up)                                                                                \
    X(WpCamera, lens_right)                                                                        \
    X(WpCamera, lens_up)                                                                           \
    X(WpCamera, filter)                                                                            \
    X(WpCamera, filter_radius)                                                                     \
    X(WpCamera, filter_scale)                                                                      \
    X(WpCamera, filter_bias)                                                                       \
    X(WpFrame, camera)                                                                             \
    X(WpFrame, width)                                                                              \
    X(WpFrame, height)                                                                             \
    X(WpFrame, seed)                                                                               \
    X(WpFrame, first_sample)                                                                       \
    X(WpFrame, sample_count)                                                                       \
    X(WpFrame, pool_size)                                                                          \
    X(WpFrame, triangle_count)                                                                     \
    X(WpFrame, sphere_count)                                                                       \
    X(WpFrame, light_count)                                                                        \
    X(WpFrame, light_area)                                                                         \
    X(WpFrame, max_depth)                                                                          \
    X(WpFrame, mirror_group_count)                                                                 \
    X(WpFrame, mirror_sphere_count)                                                                \
    X(WpFrame, path_types)                                                                         \
    X(WpFrame, emitter_count)                                                                      \
    X(WpFrame, emitter_pick)                                                                       \
    X(WpFrame, instance_count)                                                                     \
    X(WpInstance, to_world)                                                                        \
    X(WpInstance, to_object)                                                                       \
    X(WpInstance, root)                                                                            \
    X(WpInstance, first_triangle)                                                                  \
    X(WpInstance, first_primitive)                                                                 \
    X(WpInstance, mirrored)                                                                        \
    X(WpLaunch, count)                                                                             \
    X(WpLaunch, ray_queue)                                                                         \
    X(WpLaunch, from_finished)                                                                     \
    X(WpLaunch, sorted)

struct Entry {
    std::string what;
    std::size_t host;
};

std::vector<Entry> host_layout() {
    std::vector<Entry> out;
#define WP_HOST_STRUCT(T)                                                                          \
    out.push_back({"sizeof(" #T ")", sizeof(T)});                                                  \
    out.push_back({"alignof(" #T ")", alignof(T)});
#define WP_HOST_FIELD(T, f) out.push_back({"offsetof(" #T ", " #f ")", offsetof(T, f)});
    WP_LAYOUT_STRUCTS(WP_HOST_STRUCT)
    WP_LAYOUT_FIELDS(WP_HOST_FIELD)
    out.push_back({"sizeof(wp_uint)", sizeof(wp_uint)});
    out.push_back({"sizeof(wp_float)", sizeof(wp_float)});
    out.push_back({"sizeof(wp_float4)", sizeof(wp_float4)});
    out.push_back({"alignof(wp_float4)", alignof(wp_float4)});
#undef WP_HOST_STRUCT
#undef WP_HOST_FIELD
    return out;
}

// The same list, in the same order, written by a kernel.
std::string layout_source() {
    std::string s = "#include \"wp_shared.h\"\n"
                    "__kernel void layout(__global uint* out) {\n"
                    "    if (get_global_id(0) != 0) return;\n"
                    "    uint i = 0;\n";
#define WP_DEVICE_STRUCT(T)                                                                        \
    s += "    out[i++] = (uint)sizeof(" #T ");\n";                                                 \
    s += "    out[i++] = (uint)__alignof__(" #T ");\n";
#define WP_DEVICE_FIELD(T, f) s += "    out[i++] = (uint)__builtin_offsetof(" #T ", " #f ");\n";
    WP_LAYOUT_STRUCTS(WP_DEVICE_STRUCT)
    WP_LAYOUT_FIELDS(WP_DEVICE_FIELD)
#undef WP_DEVICE_STRUCT
#undef WP_DEVICE_FIELD
    s += "    out[i++] = (uint)sizeof(wp_uint);\n"
         "    out[i++] = (uint)sizeof(wp_float);\n"
         "    out[i++] = (uint)sizeof(wp_float4);\n"
         "    out[i++] = (uint)__alignof__(wp_float4);\n"
         "}\n";
    return s;
}

// Writes every field of a by-value WpFrame as raw 32-bit words, in declaration order.
const char* const kFrameEchoSource = R"CL(
#include "wp_shared.h"
__kernel void echo_frame(WpFrame frame, __global uint* out) {
    if (get_global_id(0) != 0) return;
    uint i = 0;
    float4 v[6] = {frame.camera.eye, frame.camera.forward, frame.camera.right, frame.camera.up,
                   frame.camera.lens_right, frame.camera.lens_up};
    for (int k = 0; k < 6; ++k) {
        out[i++] = as_uint(v[k].x);
        out[i++] = as_uint(v[k].y);
        out[i++] = as_uint(v[k].z);
        out[i++] = as_uint(v[k].w);
    }
    out[i++] = frame.camera.filter;
    out[i++] = as_uint(frame.camera.filter_radius);
    out[i++] = as_uint(frame.camera.filter_scale);
    out[i++] = as_uint(frame.camera.filter_bias);
    out[i++] = frame.width;
    out[i++] = frame.height;
    out[i++] = frame.seed;
    out[i++] = frame.first_sample;
    out[i++] = frame.sample_count;
    out[i++] = frame.pool_size;
    out[i++] = frame.triangle_count;
    out[i++] = frame.sphere_count;
    out[i++] = frame.light_count;
    out[i++] = as_uint(frame.light_area);
    out[i++] = frame.max_depth;
    out[i++] = frame.mirror_group_count;
    out[i++] = frame.mirror_sphere_count;
    out[i++] = frame.path_types;
}
)CL";

const char* const kRngSource = R"CL(
#include "rng.h"
__kernel void rng(uint count, __global const uint4* keys, __global const uint* dimensions,
                  __global uint* mixed, __global uint* hashed, __global float* randoms,
                  __global float* units) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint4 k = keys[i];
    mixed[i] = wp_mix32(k.x);
    hashed[i] = wp_hash(k.x, k.y, k.z, k.w);
    randoms[i] = wp_random(k.x, k.y, k.z, k.w, dimensions[i]);
    units[i] = wp_to_unit_float(k.y);
}
)CL";

} // namespace

TEST_CASE("wp_shared.h structs have the host's size, alignment and field offsets on the device",
          "[cl][layout]") {
    std::vector<Entry> host = host_layout();
    cl::Kernel kernel(program(layout_source(), "layout_test.cl"), "layout");
    cl::Buffer out = upload(std::vector<cl_uint>(host.size() + 16, 0xdeadbeefu));
    set_args(kernel, out);
    launch(kernel, 1);
    std::vector<cl_uint> device_values = download<cl_uint>(out, host.size() + 16);
    for (std::size_t i = 0; i < host.size(); ++i) {
        INFO(host[i].what);
        CHECK(device_values[i] == host[i].host);
    }
    // The kernel wrote exactly as many values as the host expects.
    CHECK(device_values[host.size()] == 0xdeadbeefu);

    // The padding rule of wp_shared.h: arrays of these structs keep 16-byte vectors aligned.
    CHECK(sizeof(WpTriangle) % 16 == 0);
    CHECK(sizeof(WpSphere) % 16 == 0);
    CHECK(sizeof(WpMaterial) % 16 == 0);
    CHECK(sizeof(WpLight) % 16 == 0);
    CHECK(sizeof(WpCamera) % 16 == 0);
    CHECK(sizeof(WpFrame) % 16 == 0);
}

TEST_CASE("A WpFrame passed by value reaches the kernel field for field", "[cl][layout]") {
    WpFrame frame{};
    frame.camera.eye = float4(1.5f, -2.25f, 3.125f, 0.5f);
    frame.camera.forward = float4(0.1f, 0.2f, -0.97f, -1.0f);
    frame.camera.right = float4(1.25f, 0.0f, 0.5f, 7.0f);
    frame.camera.up = float4(-0.03f, 0.75f, 0.01f, 1e-20f);
    frame.camera.lens_right = float4(0.125f, -3.5f, 2.0f, 1e6f);
    frame.camera.lens_up = float4(-0.5f, 0.25f, 1e-7f, 0.0625f);
    frame.camera.filter = WP_FILTER_GAUSSIAN;
    frame.camera.filter_radius = 2.0f;
    frame.camera.filter_scale = 1.4142135f;
    frame.camera.filter_bias = 3.3546262e-4f;
    frame.width = 640;
    frame.height = 480;
    frame.seed = 0x9abcdef0u;
    frame.first_sample = 12345;
    frame.sample_count = 0x80000001u;
    frame.pool_size = 777;
    frame.triangle_count = 17;
    frame.sphere_count = 3;
    frame.light_count = 2;
    frame.light_area = 0.3125f;
    frame.max_depth = 1024;
    frame.mirror_group_count = 0x11111111u;
    frame.mirror_sphere_count = 0x22222222u;
    frame.path_types = 0x13u;

    std::vector<cl_uint> expected;
    for (const cl_float4* v : {&frame.camera.eye, &frame.camera.forward, &frame.camera.right,
                               &frame.camera.up, &frame.camera.lens_right, &frame.camera.lens_up})
        for (int k = 0; k < 4; ++k)
            expected.push_back(float_bits(v->s[k]));
    expected.push_back(frame.camera.filter);
    for (float f :
         {frame.camera.filter_radius, frame.camera.filter_scale, frame.camera.filter_bias})
        expected.push_back(float_bits(f));
    for (cl_uint u : {frame.width, frame.height, frame.seed, frame.first_sample, frame.sample_count,
                      frame.pool_size, frame.triangle_count, frame.sphere_count, frame.light_count})
        expected.push_back(u);
    expected.push_back(float_bits(frame.light_area));
    for (cl_uint u :
         {frame.max_depth, frame.mirror_group_count, frame.mirror_sphere_count, frame.path_types})
        expected.push_back(u);

    cl::Kernel kernel(program(kFrameEchoSource, "frame_echo_test.cl"), "echo_frame");
    cl::Buffer out = upload(std::vector<cl_uint>(expected.size(), 0));
    set_args(kernel, frame, out);
    launch(kernel, 1);
    std::vector<cl_uint> got = download<cl_uint>(out, expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        INFO("word " << i);
        CHECK(got[i] == expected[i]);
    }
}

TEST_CASE("A WpTriangle's material and normals, kept in its w lanes, read the same on the device",
          "[cl][layout]") {
    // Up to WP_TRIANGLE_INDEX_LIMIT, with the values around each power of two
    // where float's spacing changes; the lanes hold them as float values,
    // never a denormal (whose arithmetic costs the vector code extra cycles).
    const cl_uint values[] = {0u,
                              1u,
                              2u,
                              7u,
                              255u,
                              65535u,
                              65536u,
                              8388607u,
                              8388608u,
                              8388609u,
                              16777214u,
                              16777215u,
                              WP_TRIANGLE_INDEX_LIMIT};
    std::vector<WpTriangle> triangles;
    for (cl_uint material : values)
        for (cl_uint normals : values) {
            WpTriangle t{};
            t.v0 = float4(1.0f, 2.0f, 3.0f);
            t.v1 = float4(-4.0f, 5.0f, -6.0f);
            t.v2 = float4(7.0f, 8.0f, 9.0f);
            wp_set_triangle_material(&t, material);
            wp_set_triangle_normals(&t, normals);
            REQUIRE(wp_triangle_material(&t) == material);
            REQUIRE(wp_triangle_normals(&t) == normals);
            CHECK(double(t.v0.s[3]) == double(material)); // the value, exactly
            CHECK(double(t.v1.s[3]) == double(normals));
            CHECK(std::fpclassify(t.v0.s[3]) != FP_SUBNORMAL);
            CHECK(std::fpclassify(t.v1.s[3]) != FP_SUBNORMAL);
            CHECK(t.v0.s[0] == 1.0f); // the vertices are untouched
            CHECK(t.v1.s[2] == -6.0f);
            CHECK(t.v2.s[3] == 0.0f);
            triangles.push_back(t);
        }
    const char* source = R"CL(
#include "wp_shared.h"
__kernel void read_lanes(uint count, __global const WpTriangle* triangles, __global uint* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    WpTriangle t = triangles[i];
    out[2 * i] = wp_triangle_material(&t);
    out[2 * i + 1] = wp_triangle_normals(&t);
}
)CL";
    cl::Kernel kernel(program(source, "triangle_lanes_test.cl"), "read_lanes");
    const std::size_t n = triangles.size();
    cl::Buffer in = upload(triangles);
    cl::Buffer out = upload(std::vector<cl_uint>(2 * n, 0));
    set_args(kernel, static_cast<cl_uint>(n), in, out);
    launch(kernel, n);
    std::vector<cl_uint> got = download<cl_uint>(out, 2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        INFO("triangle " << i);
        CHECK(got[2 * i] == wp_triangle_material(&triangles[i]));
        CHECK(got[2 * i + 1] == wp_triangle_normals(&triangles[i]));
    }
}

TEST_CASE("The host refuses scenes whose triangle indices a float lane cannot hold exactly",
          "[layout]") {
    CHECK_NOTHROW(wp::check_triangle_indices(WP_TRIANGLE_INDEX_LIMIT, WP_TRIANGLE_INDEX_LIMIT));
    CHECK_THROWS_AS(wp::check_triangle_indices(WP_TRIANGLE_INDEX_LIMIT + 1u, 0),
                    std::runtime_error);
    CHECK_THROWS_AS(wp::check_triangle_indices(1, WP_TRIANGLE_INDEX_LIMIT + 1u),
                    std::runtime_error);
    // 2^24 + 1 is the first uint a float cannot hold: the limit is where it must be.
    CHECK(static_cast<cl_uint>(static_cast<float>(WP_TRIANGLE_INDEX_LIMIT + 1u)) !=
          WP_TRIANGLE_INDEX_LIMIT + 1u);
}

TEST_CASE("rng.h gives bit-identical numbers on the device and the host", "[cl][rng]") {
    // Edge keys, then random ones from a fixed seed.
    std::vector<cl_uint4> keys;
    std::vector<cl_uint> dimensions;
    auto add = [&](cl_uint a, cl_uint b, cl_uint c, cl_uint d, cl_uint dim) {
        cl_uint4 k;
        k.s[0] = a;
        k.s[1] = b;
        k.s[2] = c;
        k.s[3] = d;
        keys.push_back(k);
        dimensions.push_back(dim);
    };
    const cl_uint edges[] = {0u, 1u, 2u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
    for (cl_uint a : edges)
        for (cl_uint b : edges)
            add(a, b, a ^ b, b, (a + b) % WP_DIMS_PER_BOUNCE);
    std::mt19937 generator(20240611u);
    auto next = [&] { return static_cast<cl_uint>(generator()); };
    for (int i = 0; i < 4000; ++i)
        add(next(), next(), next(), next() % 64u, next() % WP_DIMS_PER_BOUNCE);

    const std::size_t n = keys.size();
    cl::Kernel kernel(program(kRngSource, "rng_test.cl"), "rng");
    cl::Buffer key_buffer = upload(keys);
    cl::Buffer dimension_buffer = upload(dimensions);
    cl::Buffer mixed = upload(std::vector<cl_uint>(n));
    cl::Buffer hashed = upload(std::vector<cl_uint>(n));
    cl::Buffer randoms = upload(std::vector<cl_float>(n));
    cl::Buffer units = upload(std::vector<cl_float>(n));
    set_args(kernel, static_cast<cl_uint>(n), key_buffer, dimension_buffer, mixed, hashed, randoms,
             units);
    launch(kernel, n);
    std::vector<cl_uint> got_mixed = download<cl_uint>(mixed, n);
    std::vector<cl_uint> got_hashed = download<cl_uint>(hashed, n);
    std::vector<cl_float> got_randoms = download<cl_float>(randoms, n);
    std::vector<cl_float> got_units = download<cl_float>(units, n);

    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const cl_uint* k = keys[i].s;
        float random = wp_random(k[0], k[1], k[2], k[3], dimensions[i]);
        float unit = wp_to_unit_float(k[1]);
        bool same = got_mixed[i] == wp_mix32(k[0]) &&
                    got_hashed[i] == wp_hash(k[0], k[1], k[2], k[3]) &&
                    float_bits(got_randoms[i]) == float_bits(random) &&
                    float_bits(got_units[i]) == float_bits(unit);
        if (!same && mismatches++ < 5) {
            INFO("key " << k[0] << ", " << k[1] << ", " << k[2] << ", " << k[3] << " dimension "
                        << dimensions[i]);
            CHECK(got_mixed[i] == wp_mix32(k[0]));
            CHECK(got_hashed[i] == wp_hash(k[0], k[1], k[2], k[3]));
            CHECK(got_randoms[i] == random);
            CHECK(got_units[i] == unit);
        }
        // Every number lies in [0, 1).
        if (!(random >= 0.0f && random < 1.0f))
            ++mismatches;
    }
    CHECK(mismatches == 0);
    // The largest 24-bit value stays below 1, and the hash is not the identity.
    CHECK(wp_to_unit_float(0xffffffffu) < 1.0f);
    CHECK(wp_to_unit_float(0xffffffffu) == 1.0f - 1.0f / 16777216.0f);
    CHECK(wp_mix32(1u) != 1u);
    // wp_random uses counter bounce * WP_DIMS_PER_BOUNCE + dimension.
    CHECK(wp_random(7u, 8u, 9u, 3u, WP_DIM_ROULETTE) ==
          wp_to_unit_float(wp_hash(7u, 8u, 9u, 3u * WP_DIMS_PER_BOUNCE + WP_DIM_ROULETTE)));
}

TEST_CASE("The counter indices of wp_shared.h are distinct entries of the counter buffer",
          "[cl][layout]") {
    // Kernels bump these with atomics in one buffer of WP_COUNTER_COUNT words:
    // two roles sharing an entry would corrupt both queues' lengths.
    const cl_uint counters[] = {WP_COUNTER_QUEUE_A,  WP_COUNTER_QUEUE_B, WP_COUNTER_SHADOW_RAYS,
                                WP_COUNTER_FINISHED, WP_COUNTER_CAPPED,  WP_COUNTER_NONFINITE};
    std::set<cl_uint> distinct;
    for (cl_uint c : counters) {
        INFO("counter " << c);
        CHECK(c < WP_COUNTER_COUNT);
        distinct.insert(c);
    }
    CHECK(distinct.size() == std::size(counters));
}
