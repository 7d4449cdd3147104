// Stage 3, shade: one call on hand-made hits, against double-precision host
// models of mirror reflection, emission, next-event estimation and roulette,
// with the random numbers taken from rng.h on the host.
#include "render/device_scene.hpp"
#include "rng.h"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {
std::vector<cl_uint> queues_input_half(const std::vector<cl_uint>& queues, std::size_t n) {
    return std::vector<cl_uint>(queues.begin(), queues.begin() + std::ptrdiff_t(n));
}
} // namespace

namespace {

enum Material : cl_uint { kDiffuse = 0, kMirror = 1, kEmitter = 2, kDark = 3 };
enum Triangle : cl_uint { kFloor = 0, kLightA = 1, kLightB = 2, kMirrorWall = 3, kDarkFloor = 4 };
constexpr cl_uint kMirrorBall = 5; // the sphere: primitive number triangle_count + 0

wp::Scene shade_scene() {
    wp::Scene scene;
    auto material = [&](wp::MaterialKind kind, glm::dvec3 reflectance, glm::dvec3 emission) {
        wp::Material m;
        m.kind = kind;
        m.reflectance = reflectance;
        m.emission = emission;
        scene.materials.push_back(m);
    };
    material(wp::MaterialKind::Diffuse, {0.8, 0.6, 0.4}, {0, 0, 0});
    material(wp::MaterialKind::Mirror, {0.9, 0.5, 0.7}, {0, 0, 0});
    material(wp::MaterialKind::Emitter, {0, 0, 0}, {4, 3, 2});
    material(wp::MaterialKind::Diffuse, {0.05, 0.1, 0.02}, {0, 0, 0});
    auto triangle = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, cl_uint m) {
        wp::Triangle t;
        t.v = {a, b, c};
        t.material = m;
        scene.triangles.push_back(t);
    };
    triangle({-5, 0, -5}, {-5, 0, 5}, {5, 0, -5}, kDiffuse); // floor, facing +y
    triangle({-1, 4, -1}, {1, 4, -1}, {-1, 4, 1}, kEmitter); // light A, area 2, facing -y
    triangle({1, 4, -1}, {4, 4, 2}, {1, 4, 2}, kEmitter);    // light B, area 4.5, facing -y
    triangle({3, 0, -3}, {3, 2, -3}, {5, 0, -1}, kMirror);   // mirror wall, facing (1, 0, -1)
    triangle({-5, -1, -5}, {-5, -1, 5}, {5, -1, -5}, kDark); // dark floor below, facing +y
    wp::Sphere ball;
    ball.center = {0, 2, -3};
    ball.radius = 1.0;
    ball.material = kMirror;
    scene.spheres.push_back(ball);
    scene.camera.width = 1;
    scene.camera.height = 1;
    return scene;
}

D3 unit_normal(const WpTriangle& t) {
    return normalize(cross(triangle_vertex(t, 1) - triangle_vertex(t, 0),
                           triangle_vertex(t, 2) - triangle_vertex(t, 0)));
}

D3 rgb(const glm::dvec3& v) {
    return {v.x, v.y, v.z};
}

// One path slot going into shade.
struct PathIn {
    D3 origin, hit_point; // the ray runs from origin to hit_point
    cl_uint primitive = WP_NO_HIT;
    D3 throughput{1, 1, 1}, radiance{0, 0, 0};
    cl_uint depth = 0, flags = WP_PATH_SPECULAR, pixel = 0, sample = 0;
    D3 last_vertex{0, 0, 0}; // mirror_vertex: the last non-delta vertex and its BSDF pdf
    double last_pdf = 0.0;
};

constexpr cl_uint kSeed = 1234, kMaxDepth = 5;

// Every slot works on its own sample (path_sample), as slots do once the
// pool regenerates paths; the kernel must key its random numbers with it.
constexpr cl_uint sample_of(cl_uint slot) {
    return 3u + 5u * slot;
}

double random(cl_uint pixel, cl_uint sample, cl_uint depth, cl_uint dimension) {
    return wp_random(kSeed, pixel, sample, depth, dimension);
}

// The first pixel from `start` on whose random numbers satisfy `ok`.
template <typename Predicate> cl_uint find_pixel(cl_uint start, Predicate ok) {
    for (cl_uint pixel = start;; ++pixel)
        if (ok(pixel))
            return pixel;
}

} // namespace

TEST_CASE("shade: mirrors, emitters, next-event estimation and roulette on hand-made hits",
          "[cl][shade]") {
    const wp::Scene scene = shade_scene();
    const wp::DeviceScene flat = wp::flatten_scene(scene);
    REQUIRE(flat.lights.size() == 2);

    // The light table, independently: light B is picked for u >= 2 / 6.5.
    const double area_a = 2.0, area_b = 4.5, total_area = area_a + area_b;
    const double cdf_a = area_a / total_area;

    WpFrame frame{};
    frame.seed = kSeed;
    frame.triangle_count = cl_uint(flat.triangles.size());
    frame.sphere_count = cl_uint(flat.spheres.size());
    frame.light_count = cl_uint(flat.lights.size());
    frame.light_area = flat.light_area;
    frame.max_depth = kMaxDepth;

    const D3 ball_center(0, 2, -3);
    auto ball_point = [&](D3 towards) { return ball_center + normalize(towards); };
    const D3 mirror_wall_point = D3(3, 0, -3) + 0.3 * D3(0, 2, 0) + 0.3 * D3(2, 0, 2);

    // Slots; each picks a pixel whose random numbers give the case it tests.
    enum Slot : cl_uint {
        kMirrorTriangle,
        kMirrorSphere,
        kEmitterSpecular,
        kEmitterAfterDiffuse,
        kEmitterBack,
        kDiffuseToLightA,
        kDiffuseToLightB,
        kDiffuseBackFace,
        kRouletteKill,
        kDepthCap,
        kDepthCapKilled,
        kMiss,
        kEmitterAfterWeighed,
        kNotQueued,
        kPastRayCount,
        kSlotCount
    };
    std::vector<PathIn> in(kSlotCount);
    for (cl_uint slot = 0; slot < kSlotCount; ++slot)
        in[slot].sample = sample_of(slot);
    // Predicates on a pixel's random numbers for `slot` (whose sample they use).
    auto survives = [&](cl_uint slot, double survival, cl_uint depth) {
        const cl_uint sample = sample_of(slot);
        return [=](cl_uint p) { return random(p, sample, depth, WP_DIM_ROULETTE) < survival; };
    };
    auto picks = [&](cl_uint slot, bool light_b, double survival, cl_uint depth) {
        const cl_uint sample = sample_of(slot);
        return [=](cl_uint p) {
            double u = random(p, sample, depth, WP_DIM_LIGHT_PICK);
            return std::fabs(u - cdf_a) > 1e-3 && (u >= cdf_a) == light_b &&
                   random(p, sample, depth, WP_DIM_ROULETTE) < survival;
        };
    };
    // Whole-slot copies keep the slot's own sample.
    auto copy_path = [&](cl_uint to, cl_uint from) {
        in[to] = in[from];
        in[to].sample = sample_of(to);
    };

    auto place = [&](cl_uint slot, PathIn path) {
        path.sample = sample_of(slot);
        in[slot] = path;
    };
    place(kMirrorTriangle, {{0, 0.5, 0}, mirror_wall_point, kMirrorWall});
    in[kMirrorTriangle].pixel = find_pixel(100, survives(kMirrorTriangle, 0.9, 0));

    place(kMirrorSphere, {{0, 2, 0}, ball_point({0.3, 0.2, 1}), kMirrorBall});
    in[kMirrorSphere].throughput = {0.5, 0.25, 1.0}; // x reflectance: max 0.7
    in[kMirrorSphere].depth = 2;
    in[kMirrorSphere].flags = 0;
    in[kMirrorSphere].pixel = find_pixel(200, survives(kMirrorSphere, 0.7, 2));

    place(kEmitterSpecular, {{-0.5, 1, -0.5}, {-0.5, 4, -0.5}, kLightA});
    in[kEmitterSpecular].throughput = {0.5, 2, 1};
    in[kEmitterSpecular].radiance = {0.1, 0.2, 0.3};
    copy_path(kEmitterAfterDiffuse, kEmitterSpecular);
    in[kEmitterAfterDiffuse].flags = 0;
    place(kEmitterBack, {{-0.5, 5, -0.5}, {-0.5, 4, -0.5}, kLightA});
    in[kEmitterBack].radiance = {0.1, 0.2, 0.3};

    place(kDiffuseToLightA, {{-1, 2.5, 0.5}, {-2, 0, -1}, kFloor});
    in[kDiffuseToLightA].throughput = {1, 0.5, 0.25}; // x reflectance: max 0.8
    in[kDiffuseToLightA].depth = 1;
    in[kDiffuseToLightA].pixel = find_pixel(300, picks(kDiffuseToLightA, false, 0.8, 1));
    // The light point next-event estimation at kDiffuseToLightA samples, in
    // double, with the random numbers its pixel gives it.
    auto light_point_of = [&](cl_uint slot) {
        const PathIn& p = in[slot];
        double u_pick = random(p.pixel, p.sample, p.depth, WP_DIM_LIGHT_PICK);
        double u = random(p.pixel, p.sample, p.depth, WP_DIM_LIGHT_U);
        double v = random(p.pixel, p.sample, p.depth, WP_DIM_LIGHT_V);
        const WpTriangle& light = flat.triangles[u_pick < cdf_a ? kLightA : kLightB];
        double su = std::sqrt(u), b0 = 1.0 - su, b1 = v * su;
        return b0 * triangle_vertex(light, 0) + b1 * triangle_vertex(light, 1) +
               (1.0 - b0 - b1) * triangle_vertex(light, 2);
    };
    // The same path found by BSDF sampling at that diffuse vertex: the light
    // point hit after a weighed bounce (WP_PATH_GLOSSY), the vertex and the
    // Lambertian density of the direction in mirror_vertex. Its emission
    // weight and kDiffuseToLightA's light-sample weight must sum to 1.
    place(kEmitterAfterWeighed,
          {in[kDiffuseToLightA].hit_point, light_point_of(kDiffuseToLightA), kLightA});
    in[kEmitterAfterWeighed].throughput = {0.5, 2, 1};
    in[kEmitterAfterWeighed].radiance = {0.1, 0.2, 0.3};
    in[kEmitterAfterWeighed].flags = WP_PATH_GLOSSY;
    in[kEmitterAfterWeighed].last_vertex = in[kDiffuseToLightA].hit_point;
    in[kEmitterAfterWeighed].last_pdf =
        dot(D3(0, 1, 0),
            normalize(in[kEmitterAfterWeighed].hit_point - in[kDiffuseToLightA].hit_point)) /
        M_PI;

    place(kDiffuseToLightB, {{2, 3, 1}, {-1.5, 0, -2.5}, kFloor});
    in[kDiffuseToLightB].throughput = {0.7, 0.9, 0.8}; // x reflectance: max 0.56
    in[kDiffuseToLightB].radiance = {1, 1, 1};
    in[kDiffuseToLightB].flags = 0;
    in[kDiffuseToLightB].pixel = find_pixel(400, picks(kDiffuseToLightB, true, 0.56, 0));

    place(kDiffuseBackFace, {{-1, -0.5, -1}, {-1.5, 0, -1.5}, kFloor});
    in[kDiffuseBackFace].pixel = find_pixel(500, survives(kDiffuseBackFace, 0.8, 0));

    place(kRouletteKill, {{-1, -0.5, -1}, {-1, -1, -1}, kDarkFloor});
    in[kRouletteKill].radiance = {0.5, 0.5, 0.5};
    in[kRouletteKill].pixel = find_pixel(600, [](cl_uint p) {
        return random(p, sample_of(kRouletteKill), 0, WP_DIM_ROULETTE) >= 0.1;
    });

    copy_path(kDepthCap, kMirrorSphere);
    in[kDepthCap].depth = kMaxDepth;
    in[kDepthCap].pixel = find_pixel(700, survives(kDepthCap, 0.7, kMaxDepth));
    // At the cap too, but roulette ends it first: finished, and not counted as cut.
    copy_path(kDepthCapKilled, kDepthCap);
    in[kDepthCapKilled].pixel = find_pixel(800, [](cl_uint p) {
        return random(p, sample_of(kDepthCapKilled), kMaxDepth, WP_DIM_ROULETTE) >= 0.7;
    });

    // A miss keeps the radiance it brought (from earlier bounces and shadow rays).
    place(kMiss, {{0, 0, 0}, {0, 10, 0}, WP_NO_HIT});
    in[kMiss].radiance = {0.3, 0.6, 0.9};
    copy_path(kNotQueued, kDiffuseToLightA);
    copy_path(kPastRayCount, kDiffuseToLightA);

    // Upload: each slot's ray ends at its hit point.
    const std::size_t n = kSlotCount;
    std::vector<cl_float4> origin(n), direction(n), throughput(n), radiance(n), last_vertex(n);
    std::vector<cl_float> hit_t(n);
    std::vector<cl_uint> primitive(n), depth(n), flags(n), pixel(n), sample(n);
    for (std::size_t i = 0; i < n; ++i) {
        D3 segment = in[i].hit_point - in[i].origin;
        origin[i] = to_float4(in[i].origin);
        direction[i] = to_float4(normalize(segment));
        hit_t[i] = float(length(segment));
        primitive[i] = in[i].primitive;
        throughput[i] = to_float4(in[i].throughput);
        // w is not radiance: a marker that shows whether shade wrote the slot's radiance.
        radiance[i] = to_float4(in[i].radiance, 0.5);
        last_vertex[i] = to_float4(in[i].last_vertex, in[i].last_pdf);
        depth[i] = in[i].depth;
        flags[i] = in[i].flags;
        pixel[i] = in[i].pixel;
        sample[i] = in[i].sample;
    }
    std::vector<cl_uint> queue;
    for (cl_uint slot = 0; slot < n; ++slot)
        if (slot != kNotQueued && slot != kPastRayCount)
            queue.push_back(slot);
    std::reverse(queue.begin(), queue.end());
    const cl_uint ray_count = cl_uint(queue.size());
    queue.push_back(kPastRayCount);

    const cl_float4 sentinel4 = float4(-9, -9, -9, -9);
    const cl_uint sentinel = 0xeeeeeeeeu;
    // The input queue is A, survivors go to B; both hold the pool's n slots.
    frame.pool_size = cl_uint(n);
    REQUIRE(queue.size() <= n);
    std::vector<cl_uint> queues(2 * n, sentinel);
    std::copy(queue.begin(), queue.end(), queues.begin());
    DeviceBuffers buffers = stage_buffers(n, 1);
    buffers.ray_queues = upload(queues);
    buffers.ray_origin = upload(origin);
    buffers.ray_direction = upload(direction);
    buffers.hit_t = upload(hit_t);
    buffers.hit_primitive = upload(primitive);
    buffers.throughput = upload(throughput);
    buffers.radiance = upload(radiance);
    buffers.path_depth = upload(depth);
    buffers.path_flags = upload(flags);
    buffers.path_pixel = upload(pixel);
    buffers.path_sample = upload(sample);
    buffers.mirror_vertex = upload(last_vertex);
    buffers.triangles = upload(flat.triangles);
    buffers.spheres = upload(flat.spheres);
    buffers.materials = upload(flat.materials);
    buffers.lights = upload(flat.lights);
    buffers.finished_queue = upload(std::vector<cl_uint>(n, sentinel));
    buffers.shadow_queue = upload(std::vector<cl_uint>(n, sentinel));
    buffers.shadow_origin = upload(std::vector<cl_float4>(n, sentinel4));
    buffers.shadow_direction = upload(std::vector<cl_float4>(n, sentinel4));
    buffers.shadow_contribution = upload(std::vector<cl_float4>(n, sentinel4));
    // 7 paths were cut before, and the spare entries must stay as they are.
    static_assert(WP_COUNTER_COUNT == 8, "entries 6 and 7 are spare");
    std::vector<cl_uint> initial_counters(WP_COUNTER_COUNT, 0u);
    initial_counters[WP_COUNTER_QUEUE_A] = ray_count;
    initial_counters[WP_COUNTER_CAPPED] = 7u;
    initial_counters[6] = 66u;
    initial_counters[7] = 77u;
    buffers.counters = upload(initial_counters);

    // Launched for every entry of the queue, as the host launches for the
    // most the queue can hold: the one past the queue's length must idle.
    run_stage("shade", frame, make_launch(0, WP_COUNTER_QUEUE_A), buffers, queue.size());

    auto out_origin = download<cl_float4>(buffers.ray_origin, n);
    auto out_direction = download<cl_float4>(buffers.ray_direction, n);
    auto out_throughput = download<cl_float4>(buffers.throughput, n);
    auto out_radiance = download<cl_float4>(buffers.radiance, n);
    auto out_depth = download<cl_uint>(buffers.path_depth, n);
    auto out_flags = download<cl_uint>(buffers.path_flags, n);
    auto out_last_vertex = download<cl_float4>(buffers.mirror_vertex, n);
    auto out_queues = download<cl_uint>(buffers.ray_queues, 2 * n);
    // Queue A is read, never written.
    CHECK(std::vector<cl_uint>(out_queues.begin(), out_queues.begin() + std::ptrdiff_t(n)) ==
          queues_input_half(queues, n));
    std::vector<cl_uint> out_next(out_queues.begin() + std::ptrdiff_t(n), out_queues.end());
    auto out_finished = download<cl_uint>(buffers.finished_queue, n);
    auto out_shadow_queue = download<cl_uint>(buffers.shadow_queue, n);
    auto out_shadow_origin = download<cl_float4>(buffers.shadow_origin, n);
    auto out_shadow_direction = download<cl_float4>(buffers.shadow_direction, n);
    auto out_contribution = download<cl_float4>(buffers.shadow_contribution, n);
    auto out_counters = download<cl_uint>(buffers.counters, WP_COUNTER_COUNT);

    // Which paths continue, which end, and which queue a shadow ray.
    const std::set<cl_uint> continuing = {kMirrorTriangle, kMirrorSphere, kDiffuseToLightA,
                                          kDiffuseToLightB, kDiffuseBackFace};
    const std::set<cl_uint> finished = {
        kEmitterSpecular, kEmitterAfterDiffuse, kEmitterBack, kRouletteKill,
        kDepthCap,        kDepthCapKilled,      kMiss,        kEmitterAfterWeighed};
    const std::set<cl_uint> shadowed = {kDiffuseToLightA, kDiffuseToLightB, kRouletteKill};
    REQUIRE(continuing.size() + finished.size() == ray_count); // every queued path, once
    REQUIRE(out_counters[WP_COUNTER_QUEUE_B] == continuing.size());
    REQUIRE(out_counters[WP_COUNTER_FINISHED] == finished.size());
    REQUIRE(out_counters[WP_COUNTER_SHADOW_RAYS] == shadowed.size());
    CHECK(out_counters[WP_COUNTER_QUEUE_A] == ray_count); // the input queue is not consumed
    CHECK(out_counters[WP_COUNTER_CAPPED] == 8u);         // 7 before, plus the capped path
    CHECK(out_counters[WP_COUNTER_NONFINITE] == 0u);
    CHECK(out_counters[6] == 66u);
    CHECK(out_counters[7] == 77u);
    // Each queue holds its slots exactly once (sorted lists, so a duplicate shows).
    auto entries = [](const std::vector<cl_uint>& list, std::size_t count) {
        std::vector<cl_uint> out(list.begin(), list.begin() + std::ptrdiff_t(count));
        std::sort(out.begin(), out.end());
        return out;
    };
    auto listed = [](const std::set<cl_uint>& slots) {
        return std::vector<cl_uint>(slots.begin(), slots.end());
    };
    CHECK(entries(out_next, continuing.size()) == listed(continuing));
    CHECK(out_next[continuing.size()] == sentinel);
    CHECK(entries(out_finished, finished.size()) == listed(finished));
    CHECK(out_finished[finished.size()] == sentinel);
    CHECK(entries(out_shadow_queue, shadowed.size()) == listed(shadowed));
    CHECK(out_shadow_queue[shadowed.size()] == sentinel);

    // The geometry at each hit, in double: normal, and the side the ray came from.
    auto surface_normal = [&](std::size_t slot) {
        if (in[slot].primitive == kMirrorBall)
            return normalize(in[slot].hit_point - ball_center);
        return unit_normal(flat.triangles[in[slot].primitive]);
    };
    auto material_of = [&](std::size_t slot) {
        if (in[slot].primitive == kMirrorBall)
            return scene.materials[kMirror];
        return scene.materials[scene.triangles[in[slot].primitive].material];
    };

    // The power heuristic's weight of the density `own` against `other`.
    auto power_weight = [](double own, double other) {
        return own * own / (own * own + other * other);
    };
    // Both strategies' solid-angle densities at diffuse vertex x of the
    // direction to light point y on `light` (area sampling, lights.h; the
    // cosine-weighted Lambertian sample about the normal n).
    auto light_pdf = [&](D3 x, D3 y, const WpTriangle& light) {
        D3 to_light = y - x;
        double dist = length(to_light);
        return dist * dist / (-dot(unit_normal(light), to_light / dist) * total_area);
    };
    auto bsdf_pdf = [](D3 x, D3 y, D3 normal) { return dot(normal, normalize(y - x)) / M_PI; };
    // What each strategy's weight came out as in the kernel, for kDiffuseToLightA's path.
    double light_weight_found = -1.0, bsdf_weight_found = -1.0;

    for (cl_uint slot = 0; slot < n; ++slot) {
        INFO("slot " << slot << " (pixel " << in[slot].pixel << ", sample " << in[slot].sample
                     << ")");
        const PathIn& p = in[slot];
        const D3 d = from_float4(direction[slot]);
        const bool queued = slot != kNotQueued && slot != kPastRayCount;
        const bool hit = queued && p.primitive != WP_NO_HIT;

        // Radiance: emission only on an emitter's front face, seen specularly
        // or after a weighed bounce with the power heuristic's weight (not
        // after an unweighed one, kEmitterAfterDiffuse: its light sample counted it).
        D3 expected_radiance = from_float4(radiance[slot]);
        if (slot == kEmitterSpecular)
            expected_radiance = expected_radiance + p.throughput * D3(4, 3, 2);
        if (slot == kEmitterAfterWeighed) {
            double weight = power_weight(
                p.last_pdf, light_pdf(p.last_vertex, p.hit_point, flat.triangles[kLightA]));
            REQUIRE(weight > 0.01);
            REQUIRE(weight < 0.99);
            expected_radiance = expected_radiance + p.throughput * D3(4, 3, 2) * weight;
            bsdf_weight_found =
                (out_radiance[slot].s[0] - radiance[slot].s[0]) / (p.throughput.x * 4.0);
        }
        for (int k = 0; k < 3; ++k)
            CHECK(std::fabs(out_radiance[slot].s[k] - expected_radiance[k]) <=
                  1e-6 * std::fabs(expected_radiance[k]));
        if (hit && material_of(slot).emission != glm::dvec3(0.0)) {
            // Written for every hit on a surface that emits, whether the path
            // goes on or ends here.
            CHECK(out_radiance[slot].s[3] == 0.0f);
        } else {
            // Misses, hits on surfaces that emit nothing (shade skips their
            // emission) and slots not processed keep their radiance bit for bit.
            for (int k = 0; k < 4; ++k)
                CHECK(float_bits(out_radiance[slot].s[k]) == float_bits(radiance[slot].s[k]));
        }

        if (continuing.count(slot)) {
            D3 n_surface = surface_normal(slot);
            D3 facing = dot(d, n_surface) < 0.0 ? n_surface : -n_surface;
            wp::Material m = material_of(slot);
            D3 beta = p.throughput * rgb(m.reflectance);
            double survival = std::min(1.0, std::max({beta.x, beta.y, beta.z}));
            // The pixel was chosen so that roulette lets the path go on.
            CHECK(random(p.pixel, p.sample, p.depth, WP_DIM_ROULETTE) < survival);
            D3 expected_throughput = beta / survival;
            for (int k = 0; k < 3; ++k)
                CHECK(std::fabs(out_throughput[slot].s[k] - expected_throughput[k]) <=
                      1e-6 * expected_throughput[k]);
            CHECK(out_depth[slot] == p.depth + 1);

            // The new ray leaves from the hit point, on the side the ray came from.
            D3 new_origin = from_float4(out_origin[slot]);
            CHECK(distance(new_origin, p.hit_point) < 1e-4);
            CHECK(dot(new_origin - p.hit_point, facing) > 0.0);

            D3 next = from_float4(out_direction[slot]);
            CHECK(std::fabs(length(next) - 1.0) < 1e-6);
            if (m.kind == wp::MaterialKind::Mirror) {
                D3 reflected = d - 2.0 * dot(d, facing) * facing;
                INFO("mirror: direction " << next.x << ", " << next.y << ", " << next.z
                                          << " expected " << reflected.x << ", " << reflected.y
                                          << ", " << reflected.z);
                CHECK(max_abs(next - reflected) < 1e-6);
                CHECK(out_flags[slot] == WP_PATH_SPECULAR);
            } else {
                // Cosine-weighted: the cosine to the normal is sqrt(1 - u1).
                double u1 = random(p.pixel, p.sample, p.depth, WP_DIM_BSDF_U);
                CHECK(std::fabs(dot(next, facing) - std::sqrt(1.0 - u1)) < 1e-5);
                // A Lambertian vertex is weighed (WP_MIS_EVERY_VERTEX): the
                // emission the new ray finds is weighed against the light
                // sample made here, with the vertex and its density kept.
                CHECK(out_flags[slot] == WP_PATH_GLOSSY);
                CHECK(distance(from_float4(out_last_vertex[slot]), p.hit_point) < 1e-5);
                CHECK(std::fabs(out_last_vertex[slot].s[3] - dot(next, facing) / M_PI) < 1e-5);
            }
        } else {
            // Ended (or never touched): the path state is as it was.
            for (int k = 0; k < 4; ++k) {
                CHECK(out_throughput[slot].s[k] == throughput[slot].s[k]);
                CHECK(out_origin[slot].s[k] == origin[slot].s[k]);
                CHECK(out_direction[slot].s[k] == direction[slot].s[k]);
            }
            CHECK(out_depth[slot] == p.depth);
            CHECK(out_flags[slot] == p.flags);
        }

        if (shadowed.count(slot)) {
            // Next-event estimation with the same random numbers, in double.
            double u_pick = random(p.pixel, p.sample, p.depth, WP_DIM_LIGHT_PICK);
            const WpTriangle& light = flat.triangles[u_pick < cdf_a ? kLightA : kLightB];
            D3 light_point = light_point_of(slot);
            D3 n_surface = surface_normal(slot);
            D3 facing = dot(d, n_surface) < 0.0 ? n_surface : -n_surface;
            D3 to_light = light_point - p.hit_point;
            double dist = length(to_light);
            D3 wi = to_light / dist;
            double cos_surface = dot(facing, wi), cos_light = -dot(unit_normal(light), wi);
            REQUIRE(cos_surface > 0.0);
            REQUIRE(cos_light > 0.0);
            D3 rho = rgb(material_of(slot).reflectance);
            D3 unweighted = p.throughput * rho / M_PI * D3(4, 3, 2) *
                            (cos_surface * cos_light / (dist * dist) * total_area);
            // Weighed by the power heuristic against the Lambertian sample.
            D3 expected = unweighted * power_weight(light_pdf(p.hit_point, light_point, light),
                                                    bsdf_pdf(p.hit_point, light_point, facing));
            if (slot == kDiffuseToLightA)
                light_weight_found = out_contribution[slot].s[0] / unweighted.x;
            for (int k = 0; k < 3; ++k) {
                INFO("channel " << k << ": got " << out_contribution[slot].s[k] << ", expected "
                                << expected[k]);
                CHECK(std::fabs(out_contribution[slot].s[k] - expected[k]) <= 1e-4 * expected[k]);
            }
            CHECK(distance(from_float4(out_shadow_origin[slot]), p.hit_point) < 1e-4);
            CHECK(dot(from_float4(out_shadow_origin[slot]) - p.hit_point, facing) > 0.0);
            CHECK(max_abs(from_float4(out_shadow_direction[slot]) - wi) < 1e-5);
            // The segment stops just short of the light point.
            double segment = out_shadow_direction[slot].s[3];
            CHECK(segment < dist);
            CHECK(segment > dist * (1.0 - 1e-4));
        } else {
            for (int k = 0; k < 4; ++k) {
                CHECK(out_shadow_origin[slot].s[k] == -9.0f);
                CHECK(out_shadow_direction[slot].s[k] == -9.0f);
                CHECK(out_contribution[slot].s[k] == -9.0f);
            }
        }
    }
    // The two strategies' weights of the one path x -> y, as the kernel
    // computed them, sum to 1.
    INFO("light sample's weight " << light_weight_found << ", BSDF sample's " << bsdf_weight_found);
    CHECK(light_weight_found > 0.0);
    CHECK(bsdf_weight_found > 0.0);
    CHECK(std::fabs(light_weight_found + bsdf_weight_found - 1.0) < 1e-5);
    // Both lights were sampled, by the light table's cdf.
    CHECK(random(in[kDiffuseToLightA].pixel, in[kDiffuseToLightA].sample, 1, WP_DIM_LIGHT_PICK) <
          cdf_a);
    CHECK(random(in[kDiffuseToLightB].pixel, in[kDiffuseToLightB].sample, 0, WP_DIM_LIGHT_PICK) >
          cdf_a);
}

// Kernels compiled with WP_HAS_LIGHTS=1 (the general kernels, `render
// --general`) may meet a scene without emissive triangles: light sampling must
// then be skipped, not read lights[count - 1] with count = 0 (which wrapped to
// 0xffffffff and crashed PoCL before the guard moved in front of it).
TEST_CASE("shade: a diffuse hit in a scene without lights queues no shadow ray", "[cl][shade]") {
    std::vector<WpTriangle> triangles(1);
    triangles[0].v0 = float4(-5, 0, -5);
    triangles[0].v1 = float4(-5, 0, 5);
    triangles[0].v2 = float4(5, 0, -5);
    std::vector<WpMaterial> materials(1);
    // A red channel of 1 makes roulette's survival probability 1: the path goes on.
    materials[0].reflectance = float4(1.0f, 0.5f, 0.5f);
    materials[0].kind = WP_MATERIAL_DIFFUSE;
    WpFrame frame{};
    frame.triangle_count = 1;
    frame.light_count = 0;
    frame.max_depth = 5;
    auto one = [](cl_float4 v) { return upload(std::vector<cl_float4>{v}); };
    auto word = [](cl_uint v) { return upload(std::vector<cl_uint>{v}); };
    // Named, so that every buffer outlives the launch.
    // One slot; queues with room to spare, so an append at the wrong counter
    // shows. Queue roles swapped against the test above: input B, survivors
    // to A.
    const cl_uint sentinel = 0xeeeeeeeeu;
    frame.pool_size = 1;
    DeviceBuffers buffers = stage_buffers(1, 1);
    auto spare = [&] { return upload(std::vector<cl_uint>(WP_COUNTER_COUNT, sentinel)); };
    std::vector<cl_uint> queues(WP_COUNTER_COUNT, sentinel);
    queues[1] = 0u; // queue B (at offset pool_size = 1) holds slot 0
    buffers.ray_queues = upload(queues);
    buffers.ray_origin = one(float4(-1, 1, -1));
    buffers.ray_direction = one(float4(0, -1, 0));
    buffers.hit_t = upload(std::vector<cl_float>{1.0f});
    buffers.hit_primitive = word(0);
    buffers.throughput = one(float4(1, 1, 1));
    buffers.radiance = one(float4(0, 0, 0));
    buffers.path_depth = word(0);
    buffers.path_flags = word(WP_PATH_SPECULAR);
    buffers.path_pixel = word(0);
    buffers.path_sample = word(0);
    buffers.triangles = upload(triangles);
    buffers.spheres = upload(std::vector<WpSphere>(1));
    buffers.materials = upload(materials);
    buffers.lights = upload(std::vector<WpLight>(1));
    buffers.finished_queue = spare();
    buffers.shadow_queue = spare();
    std::vector<cl_uint> initial(WP_COUNTER_COUNT, 0u);
    initial[WP_COUNTER_QUEUE_B] = 1u;
    buffers.counters = upload(initial);
    run_stage("shade", frame, make_launch(0, WP_COUNTER_QUEUE_B), buffers, 1);
    cl::Buffer& counters = buffers.counters;
    cl::Buffer& shadow_queue = buffers.shadow_queue;
    cl::Buffer& finished_queue = buffers.finished_queue;
    cl::Buffer& depth = buffers.path_depth;
    std::vector<cl_uint> out = download<cl_uint>(counters, WP_COUNTER_COUNT);
    CHECK(out[WP_COUNTER_SHADOW_RAYS] == 0u);
    CHECK(download<cl_uint>(shadow_queue, WP_COUNTER_COUNT) ==
          std::vector<cl_uint>(WP_COUNTER_COUNT, sentinel));
    // The path goes on, in queue A (the counter it was told), and does not end.
    CHECK(out[WP_COUNTER_QUEUE_A] == 1u);
    CHECK(out[WP_COUNTER_QUEUE_B] == 1u);
    CHECK(out[WP_COUNTER_FINISHED] == 0u);
    std::vector<cl_uint> expected_queues = queues;
    expected_queues[0] = 0u; // queue A's first entry
    CHECK(download<cl_uint>(buffers.ray_queues, WP_COUNTER_COUNT) == expected_queues);
    CHECK(download<cl_uint>(finished_queue, WP_COUNTER_COUNT) ==
          std::vector<cl_uint>(WP_COUNTER_COUNT, sentinel));
    CHECK(download<cl_uint>(depth, 1)[0] == 1u);
}
