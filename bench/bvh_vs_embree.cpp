// wavepath_bench_bvh: wavepath's hierarchy and kernel traversal side by side
// with Embree 3 on the same rays (docs/performance.md).
//
// For each size: the room of bench/room.json around a displaced sphere of
// 12 N^2 triangles (N = 0: the room alone), wavepath tracing it with its
// hierarchy. Or, with --scene, one scene as it is (the hexroom: its own
// traversal plan, analytic spheres as Embree's sphere primitives). Both
// renderers trace the same float32 primitives (wavepath's DeviceScene) and
// the same rays:
//   incoherent: origins uniform in the scene's box (with --scene: in its free
//               space), directions uniform;
//   camera:     one jittered ray per pixel of the scene's camera;
//   bounce:     cosine-sampled from the camera rays' hits (Embree's hits);
//   shadow:     the incoherent rays with a random segment length, and from
//               the bounce origins to random points on the light.
// wavepath traces with its intersect and shadow stages alone
// (WavefrontIntegrator::time_intersect / time_shadow), Embree with
// rtcIntersect1/16 and rtcOccluded1/16 on 2 threads. A small kernel of our own
// runs wavepath's traversal once more to read its hits, which are compared
// with Embree's ray by ray.
//
// A benchmark, never a test: it prints figures (a markdown table, --json).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "cl/context.hpp"
#include "cl/program.hpp"
#include "render/device_buffers.hpp"
#include "render/device_scene.hpp"
#include "render/wavefront.hpp"
#include "report/svg_plot.hpp"
#include "scene/load.hpp"

using namespace wp;
using json = nlohmann::json;

namespace {

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// The displaced sphere of tools/make_displaced_sphere.py (a cube of N x N
// quads a face pushed onto the sphere, radius 1 + 0.15 f(d) with f a sum of
// 12 plane waves), with its own seeded waves (std::mt19937, not Python's
// generator: the same shape, not the same bytes), scaled by 150 and centred
// at (278, 175, 280) as in scenes/million.json.
void add_displaced_sphere(Scene& scene, int n, std::uint32_t material) {
    if (n <= 0)
        return;
    std::mt19937 rng(1);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    struct Wave {
        glm::dvec3 u;
        double k, phase, weight;
    };
    std::vector<Wave> waves;
    double total = 0.0;
    for (int i = 0; i < 12; ++i) {
        glm::dvec3 u = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        double k = 2.0 + 22.0 * unit(rng);
        waves.push_back({u, k, 2.0 * M_PI * unit(rng), 1.0 / k});
        total += 1.0 / k;
    }
    std::vector<double> warp(static_cast<std::size_t>(n) + 1);
    for (int i = 0; i <= n; ++i)
        warp[static_cast<std::size_t>(i)] = std::tan(M_PI / 4.0 * (-1.0 + 2.0 * i / n));
    auto vertex = [&](int lx, int ly, int lz) {
        glm::dvec3 d = glm::normalize(glm::dvec3(warp[static_cast<std::size_t>(lx)],
                                                 warp[static_cast<std::size_t>(ly)],
                                                 warp[static_cast<std::size_t>(lz)]));
        double f = 0.0;
        for (const Wave& w : waves)
            f += w.weight / total * std::sin(w.k * glm::dot(w.u, d) + w.phase);
        return 150.0 * (1.0 + 0.15 * f) * d + glm::dvec3(278.0, 175.0, 280.0);
    };
    const int faces[6][4] = {{0, 1, 1, 2},  {0, -1, 2, 1}, {1, 1, 2, 0},
                             {1, -1, 0, 2}, {2, 1, 0, 1},  {2, -1, 1, 0}};
    for (const auto& face : faces) {
        auto at = [&](int a, int b) {
            int l[3];
            l[face[0]] = face[1] > 0 ? n : 0;
            l[face[2]] = a;
            l[face[3]] = b;
            return vertex(l[0], l[1], l[2]);
        };
        for (int b = 0; b < n; ++b)
            for (int a = 0; a < n; ++a) {
                glm::dvec3 p00 = at(a, b), p10 = at(a + 1, b), p01 = at(a, b + 1),
                           p11 = at(a + 1, b + 1);
                scene.triangles.push_back({{p00, p10, p11}, material});
                scene.triangles.push_back({{p00, p11, p01}, material});
            }
    }
}

struct Rays {
    std::string name;
    std::vector<cl_float4> origins, directions; // direction w: segment length (shadow)
    std::size_t candidates = 0;                 // origins drawn, kept or not
};

cl_float4 f4(const glm::vec3& v, float w = 0.0f) {
    return {{v.x, v.y, v.z, w}};
}
glm::vec3 v3(const cl_float4& v) {
    return {v.s[0], v.s[1], v.s[2]};
}
glm::vec3 v3(const cl_float4* v) {
    return v3(*v);
}

struct Box {
    glm::vec3 lo{1e30f}, hi{-1e30f};
};

Box bounds(const DeviceScene& ds) {
    Box b;
    for (const WpTriangle& t : ds.triangles)
        for (const cl_float4* v : {&t.v0, &t.v1, &t.v2}) {
            b.lo = glm::min(b.lo, v3(v));
            b.hi = glm::max(b.hi, v3(v));
        }
    for (const WpSphere& s : ds.spheres) {
        const float r = s.center_radius.s[3];
        b.lo = glm::min(b.lo, v3(s.center_radius) - r);
        b.hi = glm::max(b.hi, v3(s.center_radius) + r);
    }
    return b;
}

// Which origins to keep: given a candidate origin and a random unit
// direction, whether the origin lies where rays are wanted.
using OriginFilter = std::function<bool(const glm::vec3& origin, const glm::vec3& probe)>;

// Origins uniform in the box shrunk by 1 % (of them those `keep` keeps, when
// given), directions uniform on the sphere, segment lengths uniform in
// (0, half the box's diagonal).
Rays incoherent_rays(const Box& box, std::size_t count, std::uint32_t seed,
                     const OriginFilter& keep = nullptr) {
    Rays r{"incoherent", {}, {}};
    glm::vec3 centre = 0.5f * (box.lo + box.hi), half = 0.495f * (box.hi - box.lo);
    float diagonal = glm::length(box.hi - box.lo);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::normal_distribution<float> normal;
    auto direction = [&] {
        return glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
    };
    while (r.origins.size() < count) {
        glm::vec3 o = centre + half * glm::vec3(u(rng), u(rng), u(rng));
        ++r.candidates;
        if (keep && !keep(o, direction()))
            continue;
        glm::vec3 d = direction();
        r.origins.push_back(f4(o));
        r.directions.push_back(f4(d, 0.25f * diagonal * (u(rng) + 1.0f)));
    }
    return r;
}

// One ray through a jittered point of every pixel, as kernels/generate.cl.
Rays camera_rays(const DeviceScene& ds, std::uint32_t seed) {
    Rays r{"camera", {}, {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const WpCamera& c = ds.camera;
    for (int y = 0; y < ds.height; ++y)
        for (int x = 0; x < ds.width; ++x) {
            float sx = 2.0f * (float(x) + u(rng)) / float(ds.width) - 1.0f;
            float sy = 1.0f - 2.0f * (float(y) + u(rng)) / float(ds.height);
            glm::vec3 d = glm::normalize(v3(c.forward) + sx * v3(c.right) + sy * v3(c.up));
            r.origins.push_back(c.eye);
            r.directions.push_back(f4(d));
        }
    return r;
}

// ---- Shadow rays reordered for locality (--shadow-orders) ------------------
//
// Issue #35's third any-hit attempt: whether tracing a shadow queue in an
// order where consecutive rays start near each other (so that they walk the
// same nodes and leaves while those are in the caches) pays for a sort
// before the shadow launch. Tried here on the host first, where it costs
// minutes to find out; the rays' answers do not depend on their order.

// Spreads the low 10 bits of v to every third bit (bit i to bit 3 i).
std::uint32_t spread_bits(std::uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

// The rays in `order` (ray indices), named name-label.
Rays permuted(const Rays& rays, const std::vector<std::uint32_t>& order, const std::string& label) {
    Rays r{rays.name + "-" + label, {}, {}, rays.candidates};
    r.origins.reserve(order.size());
    r.directions.reserve(order.size());
    for (std::uint32_t i : order) {
        r.origins.push_back(rays.origins[i]);
        r.directions.push_back(rays.directions[i]);
    }
    return r;
}

// The origins' box, which the Morton codes below divide into cells.
Box origin_box(const Rays& rays) {
    Box box;
    for (const cl_float4& o : rays.origins) {
        box.lo = glm::min(box.lo, v3(o));
        box.hi = glm::max(box.hi, v3(o));
    }
    return box;
}

// A host order, by std::sort on one thread: "origin", a 30-bit Morton code
// of the origin in the origins' box (10 bits an axis); "octant", the
// direction's octant (3 bits) above a 27-bit Morton code of the origin (9
// bits an axis); "shuffled", a random order (what a queue loses of its
// order once paths end and restart at random, for comparison). Ties keep
// the rays' order.
std::vector<std::uint32_t> host_order(const Rays& rays, const std::string& order,
                                      double& sort_seconds) {
    const std::size_t n = rays.origins.size();
    const Box box = origin_box(rays);
    const glm::vec3 extent = glm::max(box.hi - box.lo, glm::vec3(1e-30f));
    const double start = now();
    std::vector<std::uint32_t> index(n);
    if (order == "shuffled") {
        for (std::uint32_t i = 0; i < n; ++i)
            index[i] = i;
        std::shuffle(index.begin(), index.end(), std::mt19937(4));
    } else {
        std::vector<std::uint64_t> keyed(n); // key above, ray index below
        const bool octant = order == "octant";
        const float cells = octant ? 511.0f : 1023.0f;
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 q = (v3(rays.origins[i]) - box.lo) / extent * cells;
            std::uint32_t key = spread_bits(std::uint32_t(q.x)) |
                                spread_bits(std::uint32_t(q.y)) << 1 |
                                spread_bits(std::uint32_t(q.z)) << 2;
            if (octant) {
                const cl_float4& d = rays.directions[i];
                key |= std::uint32_t((d.s[0] < 0.0f) | (d.s[1] < 0.0f) << 1 | (d.s[2] < 0.0f) << 2)
                       << 27;
            }
            keyed[i] = std::uint64_t(key) << 32 | i;
        }
        std::sort(keyed.begin(), keyed.end());
        for (std::size_t i = 0; i < n; ++i)
            index[i] = std::uint32_t(keyed[i] & 0xffffffffu);
    }
    sort_seconds = now() - start;
    return index;
}

// The order a sort before the shadow launch could make on the device: a
// counting sort of the rays by a Morton code of the origin with
// `axis_bits` bits an axis, in three launches (count each cell, prefix
// sums over the cells by one work-item, each ray written at its cell's
// cursor). Within a cell the order is whichever work-item came first.
// A prototype in the bench alone, to measure what the sort costs on the
// device and what its order is worth to the traversal.
const char* kOrderSource = R"CLC(
static uint wp_spread_bits(uint v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

__kernel void order_count(uint count, __global const float4* origins, float4 low, float4 scale,
                          uint axis_cells, __global uint* keys, __global uint* counts) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float4 q = (origins[i] - low) * scale;
    uint x = min((uint)max(q.x, 0.0f), axis_cells - 1u);
    uint y = min((uint)max(q.y, 0.0f), axis_cells - 1u);
    uint z = min((uint)max(q.z, 0.0f), axis_cells - 1u);
    uint key = wp_spread_bits(x) | wp_spread_bits(y) << 1 | wp_spread_bits(z) << 2;
    keys[i] = key;
    atomic_inc(&counts[key]);
}

__kernel void order_scan(uint key_count, __global uint* counts) {
    if (get_global_id(0) != 0u)
        return;
    uint sum = 0u;
    for (uint k = 0u; k < key_count; ++k) {
        uint c = counts[k];
        counts[k] = sum;
        sum += c;
    }
}

__kernel void order_scatter(uint count, __global const uint* keys, __global uint* cursors,
                            __global uint* order) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    order[atomic_inc(&cursors[keys[i]])] = i;
}
)CLC";

struct DeviceOrder {
    DeviceContext& device;
    cl::Kernel count, scan, scatter;

    explicit DeviceOrder(DeviceContext& d) : device(d) {
        BuiltProgram built =
            build_program(device.context, device.info.device, kOrderSource, "bench_order.cl", "");
        count = cl::Kernel(built.program, "order_count");
        scan = cl::Kernel(built.program, "order_scan");
        scatter = cl::Kernel(built.program, "order_scatter");
    }

    // The rays' order by cells of `axis_bits` bits an axis; *seconds: the
    // best of `repetitions` sorts (zeroing, three launches, finish), the
    // origins already on the device as in a render.
    std::vector<std::uint32_t> run(const Rays& rays, int axis_bits, int repetitions,
                                   double& seconds) {
        const std::size_t n = rays.origins.size();
        const std::size_t keys = std::size_t(1) << (3 * axis_bits);
        const float cells = float(1u << axis_bits);
        const Box box = origin_box(rays);
        const glm::vec3 scale = cells / glm::max(box.hi - box.lo, glm::vec3(1e-30f));
        cl::Buffer origins(device.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                           sizeof(cl_float4) * std::max<std::size_t>(n, 1),
                           const_cast<cl_float4*>(rays.origins.data()));
        cl::Buffer key_of(device.context, CL_MEM_READ_WRITE,
                          sizeof(cl_uint) * std::max<std::size_t>(n, 1));
        cl::Buffer counts(device.context, CL_MEM_READ_WRITE, sizeof(cl_uint) * keys);
        cl::Buffer order(device.context, CL_MEM_READ_WRITE,
                         sizeof(cl_uint) * std::max<std::size_t>(n, 1));
        count.setArg(0, cl_uint(n));
        count.setArg(1, origins);
        count.setArg(2, f4(box.lo));
        count.setArg(3, f4(scale));
        count.setArg(4, cl_uint(1u << axis_bits));
        count.setArg(5, key_of);
        count.setArg(6, counts);
        scan.setArg(0, cl_uint(keys));
        scan.setArg(1, counts);
        scatter.setArg(0, cl_uint(n));
        scatter.setArg(1, key_of);
        scatter.setArg(2, counts);
        scatter.setArg(3, order);
        const cl::NDRange items((n + 63) / 64 * 64);
        seconds = 1e30;
        for (int r = 0; r < repetitions; ++r) {
            device.queue.finish();
            const double start = now();
            device.queue.enqueueFillBuffer(counts, cl_uint(0), 0, sizeof(cl_uint) * keys);
            device.queue.enqueueNDRangeKernel(count, cl::NullRange, items, cl::NDRange(64));
            device.queue.enqueueNDRangeKernel(scan, cl::NullRange, cl::NDRange(1), cl::NDRange(1));
            device.queue.enqueueNDRangeKernel(scatter, cl::NullRange, items, cl::NDRange(64));
            device.queue.finish();
            seconds = std::min(seconds, now() - start);
        }
        std::vector<std::uint32_t> out(n);
        if (n > 0)
            device.queue.enqueueReadBuffer(order, CL_TRUE, 0, sizeof(cl_uint) * n, out.data());
        return out;
    }
};

// ---- Embree ---------------------------------------------------------------

struct EmbreeMemory {
    std::atomic<long long> bytes{0}, peak{0};
};

bool monitor(void* user, ssize_t bytes, bool) {
    auto* m = static_cast<EmbreeMemory*>(user);
    long long b = m->bytes += bytes;
    long long p = m->peak.load();
    while (b > p && !m->peak.compare_exchange_weak(p, b)) {
    }
    return true;
}

// Geometry 0 holds the triangles, geometry 1 (when there are any) the
// spheres, as Embree's sphere primitives (RTC_GEOMETRY_TYPE_SPHERE_POINT: an
// analytic ray-sphere test, as wavepath's).
struct EmbreeScene {
    RTCScene scene = nullptr;
    double build_seconds = 0.0;
    long long bytes = 0;         // held after the build (geometry buffers and BVH)
    unsigned triangle_count = 0; // wavepath numbers sphere i triangle_count + i

    unsigned primitive(unsigned geometry, unsigned index) const {
        return geometry == 1 ? triangle_count + index : index;
    }
};

EmbreeScene build_embree(RTCDevice device, EmbreeMemory& memory, const DeviceScene& ds,
                         RTCBuildQuality quality) {
    EmbreeScene e;
    long long before = memory.bytes.load();
    e.scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(e.scene, quality);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, quality);
    const std::size_t n = ds.triangles.size();
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (std::size_t i = 0; i < n; ++i) {
        const WpTriangle& t = ds.triangles[i];
        const cl_float4* p[3] = {&t.v0, &t.v1, &t.v2};
        for (int k = 0; k < 3; ++k) {
            std::memcpy(v + 9 * i + 3 * k, p[k]->s, 3 * sizeof(float));
            index[3 * i + k] = unsigned(3 * i + k);
        }
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(e.scene, g, 0);
    rtcReleaseGeometry(g);
    e.triangle_count = unsigned(n);
    if (!ds.spheres.empty()) {
        RTCGeometry s = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        rtcSetGeometryBuildQuality(s, quality);
        auto* point = static_cast<float*>(rtcSetNewGeometryBuffer(
            s, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), ds.spheres.size()));
        for (std::size_t i = 0; i < ds.spheres.size(); ++i)
            std::memcpy(point + 4 * i, ds.spheres[i].center_radius.s, 4 * sizeof(float));
        rtcCommitGeometry(s);
        rtcAttachGeometryByID(e.scene, s, 1);
        rtcReleaseGeometry(s);
    }
    double start = now();
    rtcCommitScene(e.scene);
    e.build_seconds = now() - start;
    e.bytes = memory.bytes.load() - before;
    return e;
}

struct Hits {
    std::vector<float> t;            // closest hit (intersect) or 0/1 occluded (shadow)
    std::vector<unsigned> primitive; // WP_NO_HIT for a miss
};

// Traces `rays` on `threads` threads in chunks of 4096; returns wall seconds.
double embree_trace(const EmbreeScene& embree, const Rays& rays, bool shadow, int width,
                    int threads, Hits& out) {
    RTCScene scene = embree.scene;
    const std::size_t n = rays.origins.size();
    out.t.assign(n, 0.0f);
    out.primitive.assign(n, WP_NO_HIT);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (;;) {
            std::size_t begin = next.fetch_add(4096);
            if (begin >= n)
                return;
            std::size_t end = std::min(n, begin + 4096);
            if (width == 1) {
                for (std::size_t i = begin; i < end; ++i) {
                    const cl_float4 &o = rays.origins[i], &d = rays.directions[i];
                    RTCRayHit rh;
                    rh.ray.org_x = o.s[0];
                    rh.ray.org_y = o.s[1];
                    rh.ray.org_z = o.s[2];
                    rh.ray.dir_x = d.s[0];
                    rh.ray.dir_y = d.s[1];
                    rh.ray.dir_z = d.s[2];
                    rh.ray.tnear = 0.0f;
                    rh.ray.tfar = shadow ? d.s[3] : std::numeric_limits<float>::infinity();
                    rh.ray.time = 0.0f;
                    rh.ray.mask = ~0u;
                    rh.ray.id = 0;
                    rh.ray.flags = 0;
                    if (shadow) {
                        rtcOccluded1(scene, &context, &rh.ray);
                        out.t[i] = rh.ray.tfar < 0.0f ? 1.0f : 0.0f;
                    } else {
                        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                        rtcIntersect1(scene, &context, &rh);
                        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
                            out.t[i] = rh.ray.tfar;
                            out.primitive[i] = embree.primitive(rh.hit.geomID, rh.hit.primID);
                        }
                    }
                }
            } else {
                alignas(64) RTCRayHit16 rh;
                alignas(64) int valid[16];
                for (std::size_t first = begin; first < end; first += 16) {
                    for (std::size_t k = 0; k < 16; ++k) {
                        std::size_t i = first + k;
                        valid[k] = i < end ? -1 : 0;
                        std::size_t j = std::min(i, end - 1);
                        const cl_float4 &o = rays.origins[j], &d = rays.directions[j];
                        rh.ray.org_x[k] = o.s[0];
                        rh.ray.org_y[k] = o.s[1];
                        rh.ray.org_z[k] = o.s[2];
                        rh.ray.dir_x[k] = d.s[0];
                        rh.ray.dir_y[k] = d.s[1];
                        rh.ray.dir_z[k] = d.s[2];
                        rh.ray.tnear[k] = 0.0f;
                        rh.ray.tfar[k] = shadow ? d.s[3] : std::numeric_limits<float>::infinity();
                        rh.ray.time[k] = 0.0f;
                        rh.ray.mask[k] = ~0u;
                        rh.ray.id[k] = 0;
                        rh.ray.flags[k] = 0;
                        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                    }
                    if (shadow)
                        rtcOccluded16(valid, scene, &context, &rh.ray);
                    else
                        rtcIntersect16(valid, scene, &context, &rh);
                    for (std::size_t k = 0; k < 16 && first + k < end; ++k) {
                        std::size_t i = first + k;
                        if (shadow) {
                            out.t[i] = rh.ray.tfar[k] < 0.0f ? 1.0f : 0.0f;
                        } else if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
                            out.t[i] = rh.ray.tfar[k];
                            out.primitive[i] = embree.primitive(rh.hit.geomID[k], rh.hit.primID[k]);
                        }
                    }
                }
            }
        }
    };
    double start = now();
    std::vector<std::thread> pool;
    for (int i = 0; i < threads; ++i)
        pool.emplace_back(work);
    for (std::thread& t : pool)
        t.join();
    return now() - start;
}

// The material of wavepath's primitive p (a triangle, or sphere p - T).
std::uint32_t primitive_material(const DeviceScene& ds, unsigned p) {
    return p < ds.triangles.size() ? wp_triangle_material(&ds.triangles[p])
                                   : ds.spheres[p - ds.triangles.size()].material;
}

// The geometric normal of primitive p at x (the front side's; a triangle's
// front is the side its vertices wind anticlockwise on) and the magnitude of
// its coordinates, which kernels/ray_offset.h scales the offset by.
void primitive_frame(const DeviceScene& ds, unsigned p, const glm::vec3& x, glm::vec3& normal,
                     float& scale) {
    auto max_abs = [](glm::vec3 q) {
        return std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    };
    if (p < ds.triangles.size()) {
        const WpTriangle& tri = ds.triangles[p];
        glm::vec3 a = v3(tri.v0), b = v3(tri.v1), c = v3(tri.v2);
        normal = glm::normalize(glm::cross(b - a, c - a));
        scale = std::max({max_abs(a), max_abs(b), max_abs(c)});
    } else {
        const cl_float4& s = ds.spheres[p - ds.triangles.size()].center_radius;
        normal = glm::normalize(x - v3(s));
        scale = max_abs(v3(s)) + s.s[3];
    }
}

// Whether o lies in the free space of a closed scene whose surfaces all face
// that space (the hexroom's walls face into the room, its objects outwards):
// whether the closest surface along `probe` shows o its front. From inside an
// object, from behind a wall or with nothing in the way, it does not.
bool faces_origin(const EmbreeScene& embree, const DeviceScene& ds, const glm::vec3& o,
                  const glm::vec3& probe) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = probe.x;
    rh.ray.dir_y = probe.y;
    rh.ray.dir_z = probe.z;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree.scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return false;
    glm::vec3 normal;
    float scale;
    primitive_frame(ds, embree.primitive(rh.hit.geomID, rh.hit.primID), o + rh.ray.tfar * probe,
                    normal, scale);
    return glm::dot(normal, probe) < 0.0f;
}

// Bounce rays: from each camera ray's hit (on a non-emitting surface), offset
// along the normal on the side the ray came from as kernels/ray_offset.h does,
// cosine-distributed about that normal. Also the shadow rays of next-event
// estimation: from the same points to uniform points on the emitters.
void bounce_rays(const DeviceScene& ds, const Rays& camera, const Hits& hits, std::uint32_t seed,
                 Rays& bounce, Rays& light) {
    bounce = {"bounce", {}, {}};
    light = {"light", {}, {}};
    std::vector<std::uint32_t> emitters;
    for (std::uint32_t i = 0; i < ds.triangles.size(); ++i)
        if (ds.materials[wp_triangle_material(&ds.triangles[i])].kind == 2u) // WP_MATERIAL_EMITTER
            emitters.push_back(i);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (std::size_t i = 0; i < camera.origins.size(); ++i) {
        unsigned p = hits.primitive[i];
        if (p == WP_NO_HIT || ds.materials[primitive_material(ds, p)].kind == 2u)
            continue;
        glm::vec3 d = v3(camera.directions[i]);
        glm::vec3 x = v3(camera.origins[i]) + hits.t[i] * d;
        glm::vec3 n;
        float scale;
        primitive_frame(ds, p, x, n, scale);
        if (glm::dot(n, d) > 0.0f)
            n = -n;
        scale = std::max({scale, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
        glm::vec3 o = x + n * (2.0e-6f * scale + 1.0e-30f);
        glm::vec3 s = std::fabs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        glm::vec3 e1 = glm::normalize(glm::cross(s, n)), e2 = glm::cross(n, e1);
        float r = std::sqrt(u(rng)), phi = 2.0f * float(M_PI) * u(rng);
        glm::vec3 w = glm::normalize(r * std::cos(phi) * e1 + r * std::sin(phi) * e2 +
                                     std::sqrt(std::max(0.0f, 1.0f - r * r)) * n);
        bounce.origins.push_back(f4(o));
        bounce.directions.push_back(f4(w));
        if (emitters.empty())
            continue;
        const WpTriangle& l = ds.triangles[emitters[std::min<std::size_t>(
            emitters.size() - 1, std::size_t(u(rng) * float(emitters.size())))]];
        float s1 = std::sqrt(u(rng)), s2 = u(rng);
        glm::vec3 q = (1.0f - s1) * v3(l.v0) + s1 * (1.0f - s2) * v3(l.v1) + s1 * s2 * v3(l.v2);
        glm::vec3 to = q - o;
        float distance = glm::length(to);
        light.origins.push_back(f4(o));
        light.directions.push_back(f4(to / distance, distance * (1.0f - 1.0e-4f)));
    }
}

// ---- wavepath's hits, read by a kernel of our own --------------------------

const char* kCheckSource = R"CLC(
#include "traverse.h"

__kernel void check(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), wp_uint count,
                    __global const float4* origins, __global const float4* directions,
                    wp_uint shadow, __global float* t_out, __global wp_uint* hit_out) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    float3 o = origins[i].xyz, d = directions[i].xyz;
    if (shadow) {
        t_out[i] = wp_shadow_occluded(&scene, o, d, directions[i].w) ? 1.0f : 0.0f;
        hit_out[i] = WP_NO_HIT;
    } else {
        float t = 0.0f;
        hit_out[i] = wp_closest_hit(&scene, o, d, INFINITY, &t);
        t_out[i] = hit_out[i] == WP_NO_HIT ? 0.0f : t;
    }
}
)CLC";

struct Checker {
    DeviceContext& device;
    cl::Kernel kernel;
    DeviceBuffers buffers;
    WpFrame frame{};

    // `features`: the traced integrator's, so that the same traversal runs.
    Checker(DeviceContext& d, const SceneFeatures& features, const DeviceScene& ds) : device(d) {
        BuiltProgram built = build_program(device.context, device.info.device, kCheckSource,
                                           "bench_check.cl", features.build_options());
        kernel = cl::Kernel(built.program, "check");
        buffers = allocate_device_buffers(device.context, ds, 1, 1);
        frame.triangle_count = cl_uint(ds.triangles.size());
        frame.sphere_count = cl_uint(ds.spheres.size());
    }

    Hits run(const Rays& rays, bool shadow) {
        const std::size_t n = rays.origins.size();
        cl::Buffer o(device.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * n,
                     const_cast<cl_float4*>(rays.origins.data()));
        cl::Buffer d(device.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * n,
                     const_cast<cl_float4*>(rays.directions.data()));
        cl::Buffer t(device.context, CL_MEM_WRITE_ONLY, sizeof(float) * n);
        cl::Buffer h(device.context, CL_MEM_WRITE_ONLY, sizeof(cl_uint) * n);
        kernel.setArg(0, frame);
        cl_uint next = bind_scene_buffers(kernel, 1, buffers);
        kernel.setArg(next++, cl_uint(n));
        kernel.setArg(next++, o);
        kernel.setArg(next++, d);
        kernel.setArg(next++, cl_uint(shadow ? 1 : 0));
        kernel.setArg(next++, t);
        kernel.setArg(next++, h);
        device.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((n + 63) / 64 * 64),
                                          cl::NDRange(64));
        Hits out;
        out.t.resize(n);
        out.primitive.resize(n);
        device.queue.enqueueReadBuffer(t, CL_TRUE, 0, sizeof(float) * n, out.t.data());
        device.queue.enqueueReadBuffer(h, CL_TRUE, 0, sizeof(cl_uint) * n, out.primitive.data());
        return out;
    }
};

// Ray-by-ray agreement. Two closest hits agree when |t - t'| is within
// float rounding: 1e-5 of the larger of t and the ray origin's largest
// coordinate (the intersection test's rounding scales with the coordinates
// it subtracts, not with t). Then the same primitive is "same", another one
// "tie" (an edge or vertex both triangles share); "t_differs" (same
// primitive), "other" (another primitive) and "hit_miss" are disagreements.
json compare(const Hits& wp, const Hits& embree, const Rays& rays, bool shadow) {
    std::size_t same = 0, tie = 0, t_differs = 0, other = 0, hit_miss = 0, hits = 0;
    double worst = 0.0;
    json examples = json::array(); // the first disagreements, to look at
    auto example = [&](std::size_t i) {
        if (examples.size() >= 8)
            return;
        const cl_float4 &o = rays.origins[i], &d = rays.directions[i];
        examples.push_back({{"ray", i},
                            {"origin", {o.s[0], o.s[1], o.s[2]}},
                            {"direction", {d.s[0], d.s[1], d.s[2], d.s[3]}},
                            {"wavepath", {wp.primitive[i], wp.t[i]}},
                            {"embree", {embree.primitive[i], embree.t[i]}}});
    };
    for (std::size_t i = 0; i < wp.t.size(); ++i) {
        if (shadow) {
            if (wp.t[i] != embree.t[i])
                example(i);
            (wp.t[i] == embree.t[i] ? same : hit_miss)++;
            hits += embree.t[i] > 0.5f;
            continue;
        }
        bool a = wp.primitive[i] != WP_NO_HIT, b = embree.primitive[i] != WP_NO_HIT;
        hits += b;
        if (!a && !b) {
            ++same;
            continue;
        }
        if (a != b) {
            example(i);
            ++hit_miss;
            continue;
        }
        const cl_float4& o = rays.origins[i];
        double scale = std::max({double(embree.t[i]), std::fabs(double(o.s[0])),
                                 std::fabs(double(o.s[1])), std::fabs(double(o.s[2]))});
        double relative = std::fabs(double(wp.t[i]) - embree.t[i]) / scale;
        bool equal = wp.primitive[i] == embree.primitive[i];
        if (relative > 1e-5) {
            example(i);
            (equal ? t_differs : other)++;
            continue;
        }
        worst = std::max(worst, relative);
        (equal ? same : tie)++;
    }
    return {{"rays", wp.t.size()},
            {"same", same},
            {"tie", tie},
            {"t_differs", t_differs},
            {"other", other},
            {"hit_miss", hit_miss},
            {"hits_or_occluded", hits},
            {"max_relative_dt", worst},
            {"examples", examples}};
}

std::string uptime() {
    std::ifstream f("/proc/loadavg");
    std::string a, b, c;
    f >> a >> b >> c;
    return a + " " + b + " " + c;
}

long max_rss_mib() {
    rusage r{};
    getrusage(RUSAGE_SELF, &r);
    return r.ru_maxrss / 1024;
}

// The best of each figure over several runs: the shortest build, the most
// Mrays/s (each run already keeps its best of --repetitions).
json merged(const std::vector<std::string>& paths) {
    json results;
    for (const std::string& path : paths) {
        json run = json::parse(std::ifstream(path));
        if (results.is_null()) {
            results = run;
            continue;
        }
        for (std::size_t i = 0; i < results.size(); ++i) {
            json &r = results[i], &o = run.at(i);
            if (r["triangles"] != o["triangles"])
                throw std::runtime_error(path + ": other sizes than " + paths[0]);
            for (auto& [key, value] : r["build"].items())
                if (key.ends_with("_s"))
                    value = std::min(value.get<double>(), o["build"][key].get<double>());
            for (std::size_t j = 0; j < r["traced"].size(); ++j)
                for (auto& [key, value] : r["traced"][j].items())
                    if (key.ends_with("_mrays"))
                        value = std::max(value.get<double>(), o["traced"][j][key].get<double>());
            r["load_start"] =
                r["load_start"].get<std::string>() + "; " + o["load_start"].get<std::string>();
        }
    }
    return results;
}

int summarise(const json& results, const std::string& svg_path) {
    // The summary table.
    std::printf("\n| triangles | build wavepath s | build Embree medium s | build Embree high s | "
                "intersect incoherent wp / E1 / E16 Mrays/s | camera wp / E16 | bounce wp / E16 | "
                "shadow incoherent wp / E1 / E16 | shadow light wp / E16 | shadow light wp, "
                "all faces | B/tri wp / Embree medium / high |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const json& r : results) {
        auto m = [&](int i, const char* key) { return r["traced"][i][key].get<double>(); };
        std::printf(
            "| %zu | %.4f | %.4f | %.4f | %.2f / %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | "
            "%.2f / %.2f / %.2f | %.2f / %.2f | %s | %.1f / %.1f / %.1f |\n",
            r["triangles"].get<std::size_t>(), r["build"]["wavepath_bvh_s"].get<double>(),
            r["build"]["embree_medium_s"].get<double>(), r["build"]["embree_high_s"].get<double>(),
            m(0, "wavepath_mrays"), m(0, "embree_high_1_mrays"), m(0, "embree_high_16_mrays"),
            m(1, "wavepath_mrays"), m(1, "embree_high_16_mrays"), m(2, "wavepath_mrays"),
            m(2, "embree_high_16_mrays"), m(3, "wavepath_mrays"), m(3, "embree_high_1_mrays"),
            m(3, "embree_high_16_mrays"), m(4, "wavepath_mrays"), m(4, "embree_high_16_mrays"),
            r["traced"].size() > 5 && r["traced"][5]["rays"] == "light-all"
                ? std::to_string(m(5, "wavepath_mrays")).substr(0, 5).c_str()
                : "(no culling)",
            r["memory"]["wavepath_bytes_per_triangle"].get<double>(),
            r["memory"]["embree_medium_bytes_per_triangle"].get<double>(),
            r["memory"]["embree_high_bytes_per_triangle"].get<double>());
    }

    if (!svg_path.empty()) {
        LogLogPlot plot;
        plot.title = "Closest hit, 2 cores: incoherent (solid) and camera rays (dashed)";
        plot.x_label = "triangles";
        plot.y_label = "Mrays/s";
        struct Line {
            const char *key, *label, *colour;
        };
        const Line lines[] = {{"wavepath_mrays", "wavepath (OpenCL on PoCL)", "#1f77b4"},
                              {"embree_high_1_mrays", "Embree 1-ray", "#ff7f0e"},
                              {"embree_high_16_mrays", "Embree 16-ray packets", "#2ca02c"}};
        for (int set : {0, 1})
            for (const Line& line : lines) {
                const char* key = line.key;
                PlotSeries s;
                s.colour = line.colour;
                s.label = std::string(line.label) + (set == 0 ? ", incoherent" : ", camera");
                s.dashed = set == 1;
                for (const json& r : results) {
                    s.x.push_back(r["triangles"].get<double>());
                    s.y.push_back(r["traced"][set][key].get<double>());
                }
                plot.series.push_back(s);
            }
        write_svg(svg_path, plot);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app("wavepath's BVH and traversal against Embree 3 (docs/performance.md)");
    std::vector<int> resolutions{0, 9, 91, 289, 913};
    std::string device_selector = "0:0", json_path, svg_path, room = WAVEPATH_BENCH_ROOM;
    int size = 2048, repetitions = 3, threads = 2;
    std::size_t ray_count = 4000000;
    app.add_option("--resolutions", resolutions,
                   "Sphere resolutions N (12 N^2 triangles, 0: the room alone)")
        ->delimiter(',');
    app.add_option("--rays", ray_count, "Incoherent rays")->capture_default_str();
    app.add_option("--size", size, "Camera: size x size pixels (camera rays)")
        ->capture_default_str();
    app.add_option("--repetitions", repetitions, "Timed runs of each workload; the best counts")
        ->capture_default_str();
    app.add_option("--threads", threads, "Embree's threads")->capture_default_str();
    app.add_option("--device", device_selector, "OpenCL device")->capture_default_str();
    app.add_option("--room", room, "Scene around the sphere")->capture_default_str();
    std::string scene_path;
    app.add_option("--scene", scene_path,
                   "Trace this scene as it is, with its own traversal plan and its spheres "
                   "(incoherent origins in its free space) instead of the room around a "
                   "displaced sphere; --resolutions and --room are ignored")
        ->check(CLI::ExistingFile);
    app.add_option("--json", json_path, "Write every figure here");
    app.add_option("--svg", svg_path, "Write the Mrays/s plot here");
    std::vector<std::string> shadow_orders;
    app.add_option("--shadow-orders", shadow_orders,
                   "Also trace both shadow ray sets reordered on the host: origin (Morton "
                   "code of the origin), octant (direction octant, then origin), shuffled; "
                   "or on the device, a counting sort by a 12-, 15- or 18-bit Morton code "
                   "of the origin: device12, device15, device18")
        ->delimiter(',')
        ->check(
            CLI::IsMember({"origin", "octant", "shuffled", "device12", "device15", "device18"}));
    std::vector<std::string> merge;
    app.add_option("--merge", merge,
                   "Measure nothing: print the table (and write --svg) of the best figure of "
                   "each row over these --json files of runs with the same sizes");
    CLI11_PARSE(app, argc, argv);
    if (!merge.empty()) {
        json best = merged(merge);
        if (!json_path.empty())
            std::ofstream(json_path) << best.dump(1) << "\n";
        return summarise(best, svg_path);
    }

    DeviceContext device(select_device(device_selector), true);
    RTCDevice embree = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
    EmbreeMemory memory;
    rtcSetDeviceMemoryMonitorFunction(embree, monitor, &memory);
    std::printf("wavepath_bench_bvh: %s (%s), Embree %d.%d.%d with %d threads; load %s\n",
                device.info.name.c_str(), device.info.driver_version.c_str(), RTC_VERSION_MAJOR,
                RTC_VERSION_MINOR, RTC_VERSION_PATCH, threads, uptime().c_str());
    json results = json::array();
    DeviceOrder device_order(device);

    const bool as_is = !scene_path.empty();
    if (as_is)
        resolutions = {0};
    for (int n : resolutions) {
        Scene scene = load_scene(as_is ? scene_path : room);
        if (!as_is) {
            std::uint32_t white = 0;
            for (std::uint32_t m = 0; m < scene.materials.size(); ++m)
                if (scene.materials[m].name == "white")
                    white = m;
            add_displaced_sphere(scene, n, white);
        }
        scene.camera.width = scene.camera.height = size;
        json r;
        r["scene"] = as_is ? scene_path : room;
        r["resolution"] = n;
        r["triangles"] = scene.triangles.size();
        r["spheres"] = scene.spheres.size();
        r["load_start"] = uptime();
        std::printf("\n== %s: %zu triangles, %zu spheres (load %s)\n",
                    as_is ? scene_path.c_str() : ("N = " + std::to_string(n)).c_str(),
                    scene.triangles.size(), scene.spheres.size(), uptime().c_str());
        std::fflush(stdout);

        // Builds: wavepath's (flatten_scene with the hierarchy) and Embree's at
        // two qualities, alternated, best of `repetitions`.
        const bool big = scene.triangles.size() > 2000000;
        const int builds = big ? 1 : repetitions;
        double wp_build = 1e30, wp_flatten = 1e30, e_medium = 1e30, e_high = 1e30;
        BvhStats stats;
        for (int b = 0; b < builds; ++b) {
            double start = now();
            DeviceScene flat = flatten_scene(scene, true);
            wp_flatten = std::min(wp_flatten, now() - start);
            wp_build = std::min(wp_build, flat.bvh_stats.build_seconds);
            stats = flat.bvh_stats;
            for (RTCBuildQuality q : {RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH}) {
                EmbreeScene e = build_embree(embree, memory, flat, q);
                double& best = q == RTC_BUILD_QUALITY_HIGH ? e_high : e_medium;
                best = std::min(best, e.build_seconds);
                rtcReleaseScene(e.scene);
            }
        }
        r["build"] = {{"wavepath_bvh_s", wp_build},    {"wavepath_flatten_s", wp_flatten},
                      {"embree_medium_s", e_medium},   {"embree_high_s", e_high},
                      {"wavepath_nodes", stats.nodes}, {"wavepath_depth", stats.depth},
                      {"wavepath_sah", stats.sah_cost}};
        std::printf("build: wavepath %.3f s (flatten %.3f s), Embree medium %.3f s, high %.3f s\n",
                    wp_build, wp_flatten, e_medium, e_high);
        std::fflush(stdout);

        IntegratorOptions options;
        if (!as_is)
            options.traversal = Traversal::Hierarchy;
        options.pool_size = 0;
        const PreparedScene prepared = prepare_scene(scene, options);
        WavefrontIntegrator integrator(device, prepared);
        const DeviceScene& ds = *prepared.device_scene;
        const std::size_t wp_bytes =
            ds.triangles.size() * sizeof(WpTriangle) + ds.spheres.size() * sizeof(WpSphere) +
            ds.materials.size() * sizeof(WpMaterial) + ds.lights.size() * sizeof(WpLight) +
            ds.bvh_nodes.size() * sizeof(WpBvhNode);
        std::map<std::string, EmbreeScene> scenes;
        scenes["medium"] = build_embree(embree, memory, ds, RTC_BUILD_QUALITY_MEDIUM);
        scenes["high"] = build_embree(embree, memory, ds, RTC_BUILD_QUALITY_HIGH);
        const double tris = double(ds.triangles.size());
        r["memory"] = {{"wavepath_bytes", wp_bytes},
                       {"wavepath_bytes_per_triangle", double(wp_bytes) / tris},
                       {"embree_medium_bytes", scenes["medium"].bytes},
                       {"embree_medium_bytes_per_triangle", double(scenes["medium"].bytes) / tris},
                       {"embree_high_bytes", scenes["high"].bytes},
                       {"embree_high_bytes_per_triangle", double(scenes["high"].bytes) / tris}};

        // The ray sets; bounce and light rays come from Embree's camera hits.
        std::vector<Rays> sets;
        OriginFilter free_space; // with --scene: origins whose closest surface faces them
        if (as_is)
            free_space = [&](const glm::vec3& o, const glm::vec3& probe) {
                return faces_origin(scenes["medium"], ds, o, probe);
            };
        sets.push_back(incoherent_rays(bounds(ds), ray_count, 1, free_space));
        r["incoherent_origins"] = as_is ? "free space" : "box";
        r["incoherent_kept"] = double(sets[0].origins.size()) / double(sets[0].candidates);
        std::printf("incoherent origins: %s, %zu of %zu candidates kept\n",
                    as_is ? "in the free space" : "in the box", sets[0].origins.size(),
                    sets[0].candidates);
        sets.push_back(camera_rays(ds, 2));
        Hits camera_hits;
        embree_trace(scenes["medium"], sets[1], false, 1, threads, camera_hits);
        Rays bounce, light;
        bounce_rays(ds, sets[1], camera_hits, 3, bounce, light);
        sets.push_back(std::move(bounce));
        Checker checker(device, integrator.features(), ds);
        // Shadow culling (render/shadow_occluders.hpp) holds for segments
        // between points of the scene's surfaces, as the light rays are; the
        // incoherent segments may end beyond the walls, so they, and the
        // light rays once more for comparison, are traced without it.
        IntegratorOptions all_faces_options = options;
        all_faces_options.shadow_culling = false;
        const PreparedScene all_faces_prepared = prepare_scene(scene, all_faces_options);
        WavefrontIntegrator all_faces(device, all_faces_prepared);
        Checker all_faces_checker(device, all_faces.features(), *all_faces_prepared.device_scene);
        const bool culling = integrator.features().shadow_culling;
        r["shadow_culling"] = culling ? integrator.features().describe() : "off";

        json traced = json::array();
        auto trace = [&](const Rays& rays, bool shadow, const std::string& label,
                         WavefrontIntegrator& tracer, Checker& tracer_checker) {
            json t;
            t["rays"] = label;
            t["kind"] = shadow ? "shadow" : "intersect";
            t["count"] = rays.origins.size();
            const double count = double(rays.origins.size());
            double wp_best = 1e30;
            std::map<std::string, double> best;
            std::map<std::string, Hits> hits;
            // Alternate wavepath and Embree's four runs, so drift cancels.
            for (int rep = 0; rep < repetitions; ++rep) {
                double s = shadow ? tracer.time_shadow(rays.origins, rays.directions, 1)
                                  : tracer.time_intersect(rays.origins, rays.directions, 1);
                wp_best = std::min(wp_best, s);
                for (const char* quality : {"medium", "high"})
                    for (int width : {1, 16}) {
                        std::string key = std::string(quality) + "_" + std::to_string(width);
                        double e =
                            embree_trace(scenes[quality], rays, shadow, width, threads, hits[key]);
                        best[key] = best.count(key) ? std::min(best[key], e) : e;
                    }
            }
            t["wavepath_mrays"] = count / wp_best / 1e6;
            for (auto& [key, seconds] : best)
                t["embree_" + key + "_mrays"] = count / seconds / 1e6;
            Hits ours = tracer_checker.run(rays, shadow);
            t["check_vs_embree_medium_1"] = compare(ours, hits["medium_1"], rays, shadow);
            t["check_embree_16_vs_1"] = compare(hits["medium_16"], hits["medium_1"], rays, shadow);
            json brief = t["check_vs_embree_medium_1"];
            brief.erase("examples");
            std::printf("%-9s %-10s %8zu rays: wavepath %7.2f | Embree medium 1 %7.2f, 16 %7.2f | "
                        "high 1 %7.2f, 16 %7.2f Mrays/s; hits %s (load %s)\n",
                        shadow ? "shadow" : "intersect", label.c_str(), rays.origins.size(),
                        count / wp_best / 1e6, count / best["medium_1"] / 1e6,
                        count / best["medium_16"] / 1e6, count / best["high_1"] / 1e6,
                        count / best["high_16"] / 1e6, brief.dump().c_str(), uptime().c_str());
            std::fflush(stdout);
            traced.push_back(t);
        };
        for (const Rays& rays : sets)
            trace(rays, false, rays.name, integrator, checker);
        trace(sets[0], true, "incoherent", all_faces, all_faces_checker);
        trace(light, true, "light", integrator, checker);
        if (culling)
            trace(light, true, "light-all", all_faces, all_faces_checker);
        for (const std::string& order : shadow_orders) {
            for (const Rays* rays : {&sets[0], &light}) {
                double sort_seconds = 0.0;
                std::vector<std::uint32_t> index;
                const bool on_device = order.starts_with("device");
                if (on_device)
                    index = device_order.run(*rays, std::stoi(order.substr(6)) / 3, repetitions,
                                             sort_seconds);
                else
                    index = host_order(*rays, order, sort_seconds);
                const Rays sorted = permuted(*rays, index, order);
                std::printf("order %s: %s rays sorted in %.4f s (%s)\n", order.c_str(),
                            rays->name.c_str(), sort_seconds,
                            on_device ? "on the device" : "host, one thread");
                if (rays == &light)
                    trace(sorted, true, sorted.name, integrator, checker);
                else
                    trace(sorted, true, sorted.name, all_faces, all_faces_checker);
                traced.back()[on_device ? "device_sort_s" : "host_sort_s"] = sort_seconds;
            }
        }
        r["traced"] = traced;
        r["load_end"] = uptime();
        r["max_rss_mib"] = max_rss_mib();
        std::printf("memory: wavepath %.1f B/triangle, Embree medium %.1f, high %.1f; max RSS "
                    "%ld MiB\n",
                    double(wp_bytes) / tris, double(scenes["medium"].bytes) / tris,
                    double(scenes["high"].bytes) / tris, max_rss_mib());
        for (auto& [key, e] : scenes)
            rtcReleaseScene(e.scene);
        results.push_back(r);
        if (!json_path.empty())
            std::ofstream(json_path) << results.dump(1) << "\n";
    }

    rtcReleaseDevice(embree);
    return summarise(results, svg_path);
}
