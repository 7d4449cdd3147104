// Traversal through the hierarchy (kernels/bvh.h) against testing every
// primitive (the loop of kernels/traverse.h), both run by one kernel on the
// same rays: random meshes with shared edges and vertices (a triangulated
// height field), loose triangles and spheres, rays from random points, from
// points on the surfaces, and aimed at the mesh's edges and vertices. The
// closest hit must be the same primitive at the same t, bit for bit (or
// another primitive at the same t up to its rounding: the triangles around a
// shared vertex or edge), and any-hit must agree exactly. Then closed meshes: no ray from inside
// escapes.
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "render/device_scene.hpp"
#include "support/scene_builder.hpp"

using namespace wp;
using namespace wp::test;

namespace {

const char* kClosedSource = R"CLC(
#include "rng.h"
#include "traverse.h"

/* Ray i starts at origins[i] and goes to targets[i] (or, for odd i, in a hashed
 * random direction); it must hit the closed mesh around it, at t > 0. */
__kernel void closed(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), wp_uint count,
                     __global const float4* origins, __global const float4* targets,
                     __global wp_uint* misses) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    float3 o = origins[i].xyz;
    float3 d = targets[i].xyz - o;
    if (i & 1u) {
        float z = 2.0f * wp_to_unit_float(wp_mix32(i * 0x9e3779b9u)) - 1.0f;
        float phi = 6.2831853f * wp_to_unit_float(wp_mix32(i ^ 0x85ebca6bu));
        float r = sqrt(fmax(0.0f, 1.0f - z * z));
        d = (float3)(r * cos(phi), r * sin(phi), z);
    }
    float t;
    wp_uint hit = wp_closest_hit(&scene, o, d, INFINITY, &t);
    if (hit == WP_NO_HIT || !(t > 0.0f) || !wp_occluded(&scene, o, d, INFINITY))
        atomic_inc(misses);
}
)CLC";

const char* kCompareSource = R"CLC(
#include "traverse.h"

__kernel void compare(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), wp_uint count,
                      __global const float4* origins, __global const float4* directions,
                      __global float* t_out, __global wp_uint* hits_out) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    float3 o = origins[i].xyz, d = directions[i].xyz;
    float segment = directions[i].w; /* any-hit queries up to here */
    float t_bvh, t_loop, t_any;
    hits_out[4 * i + 0] = wp_closest_hit(&scene, o, d, INFINITY, &t_bvh);
    hits_out[4 * i + 1] = wp_loop_trace(&scene, o, d, INFINITY, 0, 0, &t_loop);
    hits_out[4 * i + 2] = wp_occluded(&scene, o, d, segment);
    hits_out[4 * i + 3] = wp_loop_trace(&scene, o, d, segment, 1, 0, &t_any) != WP_NO_HIT;
    t_out[2 * i + 0] = t_bvh;
    t_out[2 * i + 1] = t_loop;
}
)CLC";

struct Compared {
    std::vector<float> t;
    std::vector<cl_uint> hits;
};

Compared compare(const Scene& scene, const std::vector<cl_float4>& origins,
                 const std::vector<cl_float4>& directions) {
    const DeviceScene flat = flatten_scene(scene, true);
    REQUIRE(!flat.bvh_nodes.empty());
    SceneFeatures features = analyse_features(scene);
    features.fixed_counts = false;
    features.bvh = true;
    const cl::Program& built = program(kCompareSource, "bvh_compare.cl", features.build_options());
    cl::Kernel kernel(built, "compare");
    DeviceBuffers buffers = allocate_device_buffers(device().context, flat, 1, 1);
    WpFrame frame{};
    frame.triangle_count = cl_uint(flat.triangles.size());
    frame.sphere_count = cl_uint(flat.spheres.size());
    const std::size_t n = origins.size();
    cl::Buffer o = upload(origins), d = upload(directions);
    cl::Buffer t = upload(std::vector<float>(2 * n)), h = upload(std::vector<cl_uint>(4 * n));
    kernel.setArg(0, frame);
    cl_uint next = bind_scene_buffers(kernel, 1, buffers);
    kernel.setArg(next++, cl_uint(n));
    kernel.setArg(next++, o);
    kernel.setArg(next++, d);
    kernel.setArg(next++, t);
    kernel.setArg(next++, h);
    launch(kernel, n);
    return {download<float>(t, 2 * n), download<cl_uint>(h, 4 * n)};
}

// A height field of (cells + 1)^2 vertices over [-10, 10]^2, two triangles a
// cell (every inner edge shared), random loose triangles, and spheres.
Scene random_scene(unsigned seed, int cells, int loose, int spheres) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Scene scene;
    scene.camera = test::make_camera({0, 5, -20}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 8);
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    auto height = [&](int i, int j) {
        return 2.0 * std::sin(0.7 * i) * std::cos(0.45 * j) + 0.3 * unit(generator);
    };
    std::vector<glm::dvec3> grid;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i)
            grid.emplace_back(-10.0 + 20.0 * i / cells, height(i, j), -10.0 + 20.0 * j / cells);
    auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(j * (cells + 1) + i)]; };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            scene.triangles.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}, white});
            scene.triangles.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}, white});
        }
    for (int k = 0; k < loose; ++k) {
        glm::dvec3 c(20 * unit(generator) - 10, 6 * unit(generator) - 1, 20 * unit(generator) - 10);
        auto corner = [&] {
            return c +
                   glm::dvec3(unit(generator) - 0.5, unit(generator) - 0.5, unit(generator) - 0.5);
        };
        scene.triangles.push_back({{corner(), corner(), corner()}, white});
    }
    for (int k = 0; k < spheres; ++k)
        scene.spheres.push_back(
            {glm::dvec3(20 * unit(generator) - 10, 5 * unit(generator), 20 * unit(generator) - 10),
             0.2 + 0.8 * unit(generator), white});
    return scene;
}

cl_float4 f4(const glm::dvec3& v, double w = 0.0) {
    return float4(float(v.x), float(v.y), float(v.z), float(w));
}

} // namespace

TEST_CASE("bvh traversal: closest and any hit equal testing every primitive, for 10^5 rays on "
          "random meshes with spheres",
          "[cl][bvh]") {
    const Scene scene = random_scene(5, 40, 300, 40);
    REQUIRE(scene.triangles.size() + scene.spheres.size() > 3000);
    std::mt19937 generator(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto direction = [&] {
        const double z = 2 * unit(generator) - 1, phi = 2 * M_PI * unit(generator);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        return glm::dvec3(r * std::cos(phi), z, r * std::sin(phi));
    };
    std::vector<cl_float4> origins, directions;
    const int rays = 100000;
    for (int k = 0; k < rays; ++k) {
        glm::dvec3 o, d = direction();
        const int kind = k % 4;
        if (kind == 0) { // anywhere in the scene's box
            o = glm::dvec3(24 * unit(generator) - 12, 10 * unit(generator) - 3,
                           24 * unit(generator) - 12);
        } else if (kind == 1) { // on a surface: a point of a triangle
            const Triangle& t = scene.triangles[generator() % scene.triangles.size()];
            double a = unit(generator), b = unit(generator);
            if (a + b > 1) {
                a = 1 - a;
                b = 1 - b;
            }
            o = t.v[0] + a * (t.v[1] - t.v[0]) + b * (t.v[2] - t.v[0]);
        } else { // aimed at a vertex (2) or along a shared edge's point (3) of the field
            const Triangle& t = scene.triangles[generator() % (2 * 40 * 40)];
            const glm::dvec3 target =
                kind == 2 ? t.v[0] : t.v[0] + unit(generator) * (t.v[2] - t.v[0]);
            o = target + glm::dvec3(0.0, 3.0 + 5 * unit(generator), 0.0) + 2.0 * direction();
            d = glm::normalize(target - o);
        }
        origins.push_back(f4(o));
        directions.push_back(f4(d, 0.5 + 20 * unit(generator)));
    }
    const Compared r = compare(scene, origins, directions);
    const DeviceScene flat = flatten_scene(scene, true);
    int hits = 0, ties = 0, occluded = 0;
    for (int k = 0; k < rays; ++k) {
        const cl_uint bvh = r.hits[4 * k], loop = r.hits[4 * k + 1];
        INFO("ray " << k);
        REQUIRE((bvh == WP_NO_HIT) == (loop == WP_NO_HIT));
        if (bvh == loop) {
            REQUIRE(float_bits(r.t[2 * k]) == float_bits(r.t[2 * k + 1]));
        } else {
            // Another primitive at the same distance up to rounding (the
            // triangles around a vertex or along an edge each compute their
            // own t): allowed within 4 ulps, and counted.
            REQUIRE(std::fabs(r.t[2 * k] - r.t[2 * k + 1]) <= 4.0f * 1.2e-7f * r.t[2 * k + 1]);
            ++ties;
        }
        hits += bvh != WP_NO_HIT;
        REQUIRE(r.hits[4 * k + 2] == r.hits[4 * k + 3]);
        occluded += r.hits[4 * k + 2] != 0;
    }
    WARN("bvh: " << flat.bvh_stats.nodes << " nodes, depth " << flat.bvh_stats.depth
                 << ", SAH cost " << flat.bvh_stats.sah_cost << "; " << hits << " hits, " << ties
                 << " ties on another primitive, " << occluded << " occluded segments");
    CHECK(hits > rays / 2);
    CHECK(occluded > rays / 10);
    CHECK(ties < rays / 100);
}

TEST_CASE("bvh any hit: segments ending just short of, at and just past the nearest hit, and "
          "degenerate triangles, are blocked exactly where testing every primitive says so",
          "[cl][bvh]") {
    // The shadow rays' traversal (kernels/bvh_any_hit.h) against the loop over
    // every primitive: a random scene with degenerate triangles (repeated and
    // collinear corners) among the loose ones, rays aimed at its triangles,
    // and for each ray that hits, segments that end a few ulps short of the
    // nearest hit's t (as the loop computes it), at it, and a few ulps past it.
    Scene scene = random_scene(23, 24, 200, 12);
    std::mt19937 generator(29);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto material = scene.triangles.front().material;
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 a(20 * unit(generator) - 10, 4 * unit(generator),
                           20 * unit(generator) - 10);
        const glm::dvec3 b = a + glm::dvec3(unit(generator), unit(generator), unit(generator));
        scene.triangles.push_back({{a, b, k % 2 ? b : 0.25 * a + 0.75 * b}, material});
    }
    std::vector<cl_float4> origins, directions;
    const int rays = 20000;
    for (int k = 0; k < rays; ++k) {
        const Triangle& aim = scene.triangles[generator() % scene.triangles.size()];
        double u = unit(generator), v = unit(generator);
        if (u + v > 1)
            u = 1 - u, v = 1 - v;
        const glm::dvec3 target = aim.v[0] + u * (aim.v[1] - aim.v[0]) + v * (aim.v[2] - aim.v[0]);
        const glm::dvec3 o(24 * unit(generator) - 12, 10 * unit(generator) - 3,
                           24 * unit(generator) - 12);
        origins.push_back(f4(o));
        directions.push_back(f4(glm::normalize(target - o), INFINITY));
    }
    const Compared nearest = compare(scene, origins, directions);

    // Five segments a ray: 4 ulps short, 1 ulp short, at, 1 ulp and 4 ulps past.
    std::vector<cl_float4> segment_origins, segment_directions;
    for (int k = 0; k < rays; ++k) {
        if (nearest.hits[4 * k + 1] == WP_NO_HIT)
            continue;
        const float t = nearest.t[2 * k + 1];
        const float ends[5] = {
            std::nextafter(std::nextafter(std::nextafter(std::nextafter(t, 0.0f), 0.0f), 0.0f),
                           0.0f),
            std::nextafter(t, 0.0f), t, std::nextafter(t, INFINITY),
            std::nextafter(
                std::nextafter(std::nextafter(std::nextafter(t, INFINITY), INFINITY), INFINITY),
                INFINITY)};
        for (float end : ends) {
            segment_origins.push_back(origins[std::size_t(k)]);
            cl_float4 d = directions[std::size_t(k)];
            d.s[3] = end;
            segment_directions.push_back(d);
        }
    }
    const std::size_t segments = segment_origins.size();
    REQUIRE(segments > 5 * rays / 2);
    const Compared r = compare(scene, segment_origins, segment_directions);
    std::size_t differ = 0, blocked_short = 0, blocked_past = 0;
    for (std::size_t k = 0; k < segments; ++k) {
        differ += r.hits[4 * k + 2] != r.hits[4 * k + 3];
        blocked_short += k % 5 == 0 && r.hits[4 * k + 3] != 0;
        blocked_past += k % 5 == 4 && r.hits[4 * k + 3] != 0;
    }
    WARN("bvh any hit at the nearest hit: " << segments / 5 << " rays; blocked 4 ulps short "
                                            << blocked_short << ", 4 ulps past " << blocked_past);
    CHECK(differ == 0);
    // Both sides of the boundary were exercised: the segments short of the
    // nearest hit are mostly clear, those past it mostly blocked.
    CHECK(blocked_short < segments / 5 / 10);
    CHECK(blocked_past > segments / 5 * 9 / 10);
}

TEST_CASE("bvh shadow stage: through the hierarchy, exactly the unblocked contributions are "
          "added, for one ray, odd counts and a shuffled queue",
          "[cl][bvh][shadow]") {
    // The shadow kernel built with the hierarchy (kernels/shadow.cl through
    // bvh_any_hit.h) against the loop over every primitive, run by compare()
    // on the same segments. The queue is a shuffled subset of the slots
    // (slot 0 never queued); launches of 1, 2, 3, an odd number and all the
    // entries, each over a whole work-group.
    const Scene scene = random_scene(31, 20, 150, 10);
    std::mt19937 generator(37);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::size_t slots = 4001;
    std::vector<cl_float4> origins, directions, contributions, radiance;
    for (std::size_t k = 0; k < slots; ++k) {
        const glm::dvec3 o(24 * unit(generator) - 12, 10 * unit(generator) - 3,
                           24 * unit(generator) - 12);
        const glm::dvec3 target(20 * unit(generator) - 10, 3 * unit(generator) - 1,
                                20 * unit(generator) - 10);
        const double length = glm::length(target - o) * (0.3 + 1.2 * unit(generator));
        origins.push_back(f4(o));
        directions.push_back(f4(glm::normalize(target - o), length));
        const float f = float(k);
        contributions.push_back(float4(0.5f + f, 1.0f / (f + 2.0f), 3.0f, 0.25f));
        radiance.push_back(float4(f, -f, 0.125f * f, 1.0f));
    }
    const Compared reference = compare(scene, origins, directions);
    std::vector<cl_uint> queue(slots - 1); // slot 0 is never queued
    std::iota(queue.begin(), queue.end(), 1u);
    std::shuffle(queue.begin(), queue.end(), generator);

    const DeviceScene flat = flatten_scene(scene, true);
    SceneFeatures features = analyse_features(scene);
    features.fixed_counts = false;
    features.bvh = true;
    DeviceBuffers buffers = allocate_device_buffers(device().context, flat, slots, 1);
    buffers.shadow_queue = upload(queue);
    buffers.shadow_origin = upload(origins);
    buffers.shadow_direction = upload(directions);
    buffers.shadow_contribution = upload(contributions);
    WpFrame frame{};
    frame.triangle_count = cl_uint(flat.triangles.size());
    frame.sphere_count = cl_uint(flat.spheres.size());
    for (const std::size_t count :
         {std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(977), queue.size()}) {
        INFO(count << " queued rays");
        buffers.radiance = upload(radiance);
        run_stage("shadow", frame, make_launch(cl_uint(count), 0), buffers, count,
                  features.build_options());
        const std::vector<cl_float4> got = download<cl_float4>(buffers.radiance, slots);
        std::vector<bool> queued(slots, false);
        for (std::size_t i = 0; i < count; ++i)
            queued[queue[i]] = true;
        std::size_t blocked = 0;
        for (std::size_t k = 0; k < slots; ++k) {
            const bool is_blocked = reference.hits[4 * k + 3] != 0;
            INFO("slot " << k << (queued[k] ? ", queued" : "") << (is_blocked ? ", blocked" : ""));
            for (int c = 0; c < 4; ++c) {
                float expected = radiance[k].s[c];
                if (queued[k] && !is_blocked)
                    expected += contributions[k].s[c];
                REQUIRE(got[k].s[c] == expected);
            }
            blocked += queued[k] && is_blocked;
        }
        if (count > 100) { // both answers occur
            CHECK(blocked > count / 5);
            CHECK(blocked < count * 4 / 5);
        }
    }
}

TEST_CASE("bvh traversal: no ray from inside a closed mesh of 43200 triangles slips through an "
          "edge or vertex (10^6 rays)",
          "[cl][bvh]") {
    // A cube whose faces are 60 x 60 grids, bulged into a rounded shape. Each
    // vertex is computed from its integer grid position alone, so the faces
    // meeting at an edge share their vertices exactly: the mesh is closed.
    const int n = 60;
    Scene scene;
    scene.camera = test::make_camera({0, 0, -5}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 8);
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    auto vertex = [&](glm::ivec3 g) { // g in [0, n]^3 on the cube's surface
        glm::dvec3 p = glm::dvec3(g) * (2.0 / n) - glm::dvec3(1.0);
        return p * (1.0 + 0.1 * std::sin(3.0 * p.x) * std::cos(2.0 * p.y));
    };
    std::vector<glm::dvec3> targets;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side)
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    auto corner = [&](int i, int j) {
                        glm::ivec3 g;
                        g[axis] = side * n;
                        g[(axis + 1) % 3] = i;
                        g[(axis + 2) % 3] = j;
                        return vertex(g);
                    };
                    const glm::dvec3 p00 = corner(a, b), p10 = corner(a + 1, b),
                                     p11 = corner(a + 1, b + 1), p01 = corner(a, b + 1);
                    scene.triangles.push_back({{p00, p10, p11}, white});
                    scene.triangles.push_back({{p00, p11, p01}, white});
                    targets.push_back(p00);                   // a vertex
                    targets.push_back(0.5 * (p00 + p11));     // a diagonal edge
                    targets.push_back(0.7 * p00 + 0.3 * p10); // a grid edge
                }
    REQUIRE(scene.triangles.size() == 43200);
    const DeviceScene flat = flatten_scene(scene, true);
    SceneFeatures features = analyse_features(scene);
    REQUIRE(features.bvh);
    const cl::Program& built = program(kClosedSource, "bvh_closed.cl", features.build_options());
    cl::Kernel kernel(built, "closed");
    DeviceBuffers buffers = allocate_device_buffers(device().context, flat, 1, 1);
    WpFrame frame{};
    frame.triangle_count = cl_uint(flat.triangles.size());

    std::mt19937 generator(17);
    std::uniform_real_distribution<double> unit(-0.6, 0.6);
    const std::size_t rays = 1000000;
    std::vector<cl_float4> origins(rays), aims(rays);
    for (std::size_t i = 0; i < rays; ++i) {
        origins[i] = f4(glm::dvec3(unit(generator), unit(generator), unit(generator)));
        aims[i] = f4(targets[generator() % targets.size()]);
    }
    cl::Buffer o = upload(origins), t = upload(aims), misses = upload(std::vector<cl_uint>{0});
    kernel.setArg(0, frame);
    cl_uint next = bind_scene_buffers(kernel, 1, buffers);
    kernel.setArg(next++, cl_uint(rays));
    kernel.setArg(next++, o);
    kernel.setArg(next++, t);
    kernel.setArg(next++, misses);
    launch(kernel, rays);
    const cl_uint missed = download<cl_uint>(misses, 1)[0];
    WARN("closed mesh through the bvh: " << missed << " misses in " << rays << " rays ("
                                         << flat.bvh_stats.nodes << " nodes, depth "
                                         << flat.bvh_stats.depth << ")");
    CHECK(missed == 0);
}
