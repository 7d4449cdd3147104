// Russian roulette in shade (kernels/shade.cl, step 4; kernels/estimator.h):
// for each rule, which paths go on, their new throughput and the eta^2 they
// carry (throughput.w), against a double-precision host model of the rule,
// of the smooth dielectric's Fresnel choice and of the weights. Glass entered
// from outside and left from inside (some of those by total internal
// reflection), and diffuse floors, one of them bright enough to meet Mitsuba's
// 0.95 cap; below and from the roulette depth on. The same slots under
// Cycles' rule (sqrt of the throughput) and the relative rule (the throughput
// over the first bounce's, carried in throughput.w).
#include "render/device_scene.hpp"
#include "rng.h"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

constexpr cl_uint kSeed = 77, kMaxDepth = 64;
constexpr double kEta = 1.5;                     // the glass: int_ior 1.5, ext_ior 1
const D3 kGlassTransmittance{0.9, 0.8, 0.7};     // specular_transmittance
const D3 kGlassReflectance{1.0, 0.95, 0.9};      // specular_reflectance
const D3 kFloorReflectance{0.8, 0.6, 0.4};       // diffuse
const D3 kBrightFloorReflectance{1.0, 0.5, 0.5}; // diffuse, max 1 > 0.95

enum Primitive : cl_uint { kFloor = 0, kBrightFloor = 1, kGlassBall = 2 }; // the sphere last

wp::Scene roulette_scene() {
    wp::Scene scene;
    wp::Material floor, bright, glass;
    floor.reflectance = kFloorReflectance;
    bright.reflectance = kBrightFloorReflectance;
    glass.kind = wp::MaterialKind::Dielectric;
    glass.int_ior = kEta;
    glass.ext_ior = 1.0;
    glass.reflectance = kGlassReflectance;
    glass.transmittance = kGlassTransmittance;
    scene.materials = {floor, bright, glass};
    auto triangle = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, cl_uint m) {
        wp::Triangle t;
        t.v = {a, b, c};
        t.material = m;
        scene.triangles.push_back(t);
    };
    triangle({-5, -2, -5}, {-5, -2, 5}, {5, -2, -5}, 0);  // facing +y
    triangle({10, -2, -5}, {10, -2, 5}, {20, -2, -5}, 1); // facing +y
    wp::Sphere ball;
    ball.center = {0, 0, 0};
    ball.radius = 1.0;
    ball.material = 2;
    scene.spheres.push_back(ball);
    scene.camera.width = 1;
    scene.camera.height = 1;
    return scene;
}

double random(cl_uint pixel, cl_uint sample, cl_uint depth, cl_uint dimension) {
    return wp_random(kSeed, pixel, sample, depth, dimension);
}

// Fresnel reflectance of a smooth dielectric, eta = n_far / n_near (Hecht).
double fresnel(double cos_i, double eta) {
    const double sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin_t2 >= 1.0)
        return 1.0; // total internal reflection
    const double cos_t = std::sqrt(1.0 - sin_t2);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (cos_t - eta * cos_i) / (cos_t + eta * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

double max_of(const D3& v) {
    return std::max({v.x, v.y, v.z});
}

// One path slot going into shade.
struct PathIn {
    D3 origin, direction; // unit direction
    double t = 0.0;
    cl_uint primitive = 0, depth = 0, pixel = 0, sample = 0;
    D3 beta{1, 1, 1};
    double eta_squared = 1.0;
};

// What the host model says becomes of it; `tie` where a random number lies
// too close to a threshold for float and double to be sure to agree.
struct Expected {
    bool tie = false, survives = false, transmitted = false;
    D3 throughput;
    double eta_squared = 1.0, survival = 1.0;
};

// The rules, numbered as WP_ROULETTE_RULE (kernels/estimator.h).
enum Rule { kThroughput = 0, kMitsuba = 1, kSqrt = 2, kRelative = 3 };

Expected model(const PathIn& p, Rule rule, cl_uint roulette_depth) {
    const bool mitsuba = rule == kMitsuba;
    Expected e;
    D3 weight;
    double eta_step = 1.0;
    if (p.primitive == kGlassBall) {
        const D3 hit = p.origin + p.t * p.direction; // the ball is a unit sphere at 0
        const D3 n = normalize(hit);
        const double cos_in = dot(p.direction, n);
        const bool front = cos_in < 0.0;
        const double eta = front ? kEta : 1.0 / kEta;
        const double r = fresnel(std::fabs(cos_in), eta);
        const double u = random(p.pixel, p.sample, p.depth, WP_DIM_BSDF_U);
        e.tie = r < 1.0 && std::fabs(u - r) < 1e-5;
        e.transmitted = !(u < r);
        weight = e.transmitted ? kGlassTransmittance * (1.0 / (eta * eta)) : kGlassReflectance;
        eta_step = e.transmitted ? eta : 1.0;
    } else {
        weight = p.primitive == kFloor ? kFloorReflectance : kBrightFloorReflectance;
    }
    const D3 beta = p.beta * weight;
    e.eta_squared = mitsuba ? p.eta_squared * eta_step * eta_step : p.eta_squared;
    if (rule == kRelative && p.depth == 0) // the first bounce's throughput
        e.eta_squared = max_of(beta);
    if (p.depth + 1 >= roulette_depth)
        e.survival = rule == kMitsuba    ? std::min(0.95, max_of(beta) * e.eta_squared)
                     : rule == kSqrt     ? std::min(1.0, std::sqrt(max_of(beta)))
                     : rule == kRelative ? std::min(1.0, max_of(beta) / e.eta_squared)
                                         : std::min(1.0, max_of(beta));
    const double u = random(p.pixel, p.sample, p.depth, WP_DIM_ROULETTE);
    e.tie = e.tie || std::fabs(u - e.survival) < 1e-5;
    e.survives = u < e.survival;
    e.throughput = beta * (1.0 / e.survival);
    return e;
}

// The slots: four kinds of hit, each at depths 0 (below the roulette depth
// of the Mitsuba build, 2) and 3, for 40 pixels each.
std::vector<PathIn> roulette_paths() {
    std::vector<PathIn> paths;
    constexpr int kPixels = 40;
    for (cl_uint depth : {0u, 3u})
        for (int k = 0; k < kPixels; ++k) {
            const double s = (k + 0.5) / kPixels;
            PathIn p;
            p.depth = depth;
            p.pixel = cl_uint(paths.size());
            p.sample = 5u + p.pixel;
            // Into the glass from outside, from head-on to grazing.
            p.origin = {0.99 * s, 0.1, 5.0};
            p.direction = {0, 0, -1};
            p.t = 5.0 - std::sqrt(1.0 - p.origin.x * p.origin.x - 0.01);
            p.primitive = kGlassBall;
            p.beta = {0.3, 0.2, 0.1};
            paths.push_back(p);
            // Out of it from inside (eta^2 of the way in carried), some by
            // total internal reflection.
            p.pixel = cl_uint(paths.size());
            p.sample = 5u + p.pixel;
            p.origin = {0.5, 0.0, 0.0};
            const double a = 2.0 * 3.14159265358979 * s;
            p.direction = normalize(D3(std::cos(a), 0.2, std::sin(a)));
            const double b = dot(p.origin, p.direction), c = dot(p.origin, p.origin) - 1.0;
            p.t = -b + std::sqrt(b * b - c);
            p.beta = {0.5, 0.4, 0.3};
            p.eta_squared = kEta * kEta;
            paths.push_back(p);
            // Onto the floors from above.
            for (cl_uint floor : {kFloor, kBrightFloor}) {
                p.pixel = cl_uint(paths.size());
                p.sample = 5u + p.pixel;
                const D3 target(floor == kFloor ? -4.0 + 4.0 * s : 11.0 + 4.0 * s, -2.0,
                                -4.0 + 2.0 * s);
                p.origin = target + D3(0.3, 3.0, 0.2);
                p.direction = normalize(target - p.origin);
                p.t = length(target - p.origin);
                p.primitive = floor;
                p.beta = {0.9, 0.7, 0.5};
                p.eta_squared = floor == kFloor ? 1.0 : kEta * kEta;
                paths.push_back(p);
            }
        }
    return paths;
}

// Runs shade over `paths` with the kernels built with `options`; checks every
// slot against the model and returns how many went on, ended, were
// transmitted, and were capped by 0.95 (for the coverage checks).
struct Seen {
    int survived = 0, ended = 0, transmitted = 0, reflected = 0, capped = 0, below_one = 0;
};

Seen check_shade(const std::vector<PathIn>& paths, const std::string& options, Rule rule,
                 cl_uint roulette_depth) {
    const wp::DeviceScene flat = wp::flatten_scene(roulette_scene());
    const std::size_t n = paths.size();
    WpFrame frame{};
    frame.seed = kSeed;
    frame.triangle_count = cl_uint(flat.triangles.size());
    frame.sphere_count = cl_uint(flat.spheres.size());
    frame.max_depth = kMaxDepth;
    frame.pool_size = cl_uint(n);
    std::vector<cl_float4> origin(n), direction(n), throughput(n);
    std::vector<cl_float> hit_t(n);
    std::vector<cl_uint> primitive(n), depth(n), flags(n, WP_PATH_SPECULAR), pixel(n), sample(n);
    std::vector<cl_uint> queues(2 * n, 0xeeeeeeeeu);
    for (std::size_t i = 0; i < n; ++i) {
        origin[i] = to_float4(paths[i].origin);
        direction[i] = to_float4(paths[i].direction);
        hit_t[i] = float(paths[i].t);
        primitive[i] = paths[i].primitive;
        throughput[i] = to_float4(paths[i].beta, paths[i].eta_squared);
        depth[i] = paths[i].depth;
        pixel[i] = paths[i].pixel;
        sample[i] = paths[i].sample;
        queues[i] = cl_uint(i);
    }
    DeviceBuffers buffers = stage_buffers(n, 1);
    buffers.ray_queues = upload(queues);
    buffers.ray_origin = upload(origin);
    buffers.ray_direction = upload(direction);
    buffers.hit_t = upload(hit_t);
    buffers.hit_primitive = upload(primitive);
    buffers.throughput = upload(throughput);
    buffers.radiance = upload(std::vector<cl_float4>(n, float4(0, 0, 0, 0)));
    buffers.path_depth = upload(depth);
    buffers.path_flags = upload(flags);
    buffers.path_pixel = upload(pixel);
    buffers.path_sample = upload(sample);
    buffers.triangles = upload(flat.triangles);
    buffers.spheres = upload(flat.spheres);
    buffers.materials = upload(flat.materials);
    buffers.finished_queue = upload(std::vector<cl_uint>(n, 0xeeeeeeeeu));
    std::vector<cl_uint> counters(WP_COUNTER_COUNT, 0u);
    counters[WP_COUNTER_QUEUE_A] = cl_uint(n);
    buffers.counters = upload(counters);
    run_stage("shade", frame, make_launch(0, WP_COUNTER_QUEUE_A), buffers, n, options);

    const auto out_throughput = download<cl_float4>(buffers.throughput, n);
    const auto out_direction = download<cl_float4>(buffers.ray_direction, n);
    const auto out_depth = download<cl_uint>(buffers.path_depth, n);
    const auto out_queues = download<cl_uint>(buffers.ray_queues, 2 * n);
    const auto out_counters = download<cl_uint>(buffers.counters, WP_COUNTER_COUNT);
    std::vector<bool> went_on(n, false);
    for (cl_uint i = 0; i < out_counters[WP_COUNTER_QUEUE_B]; ++i)
        went_on[out_queues[n + i]] = true;

    Seen seen;
    for (std::size_t i = 0; i < n; ++i) {
        const PathIn& p = paths[i];
        const Expected e = model(p, rule, roulette_depth);
        if (e.tie)
            continue;
        INFO("slot " << i << ", primitive " << p.primitive << ", depth " << p.depth << ", survival "
                     << e.survival);
        REQUIRE(went_on[i] == e.survives);
        if (!e.survives) {
            ++seen.ended;
            continue;
        }
        ++seen.survived;
        seen.capped += e.survival == 0.95 ? 1 : 0;
        seen.below_one += e.survival < 1.0 ? 1 : 0;
        const D3 got = from_float4(out_throughput[i]);
        CHECK(max_abs(got - e.throughput) <= 1e-5 * max_of(e.throughput));
        CHECK(std::fabs(out_throughput[i].s[3] - e.eta_squared) <= 1e-6 * e.eta_squared);
        CHECK(out_depth[i] == p.depth + 1);
        if (p.primitive == kGlassBall) {
            // The direction says which way the kernel chose: on through the
            // surface (the incoming direction's side of the normal) if transmitted.
            const D3 n_out = normalize(p.origin + p.t * p.direction);
            const bool far_side = (dot(from_float4(out_direction[i]), n_out) > 0.0) ==
                                  (dot(p.direction, n_out) > 0.0);
            CHECK(far_side == e.transmitted);
            (e.transmitted ? seen.transmitted : seen.reflected) += 1;
        }
    }
    return seen;
}

} // namespace

TEST_CASE("roulette: Mitsuba's rule, min(0.95, max(throughput) eta^2), with eta^2 carried "
          "through the glass, against a host model",
          "[cl][shade][roulette]") {
    const std::vector<PathIn> paths = roulette_paths();
    const Seen seen =
        check_shade(paths, "-D WP_ROULETTE_RULE=1 -D WP_ROULETTE_DEPTH=2", kMitsuba, 2);
    // Every case the model separates was met.
    CHECK(seen.survived > 0);
    CHECK(seen.ended > 0);
    CHECK(seen.transmitted > 0);
    CHECK(seen.reflected > 0);
    CHECK(seen.capped > 0);
}

TEST_CASE("roulette: the default rule, min(1, max(throughput)), leaves throughput.w as it was",
          "[cl][shade][roulette]") {
    const std::vector<PathIn> paths = roulette_paths();
    const Seen seen = check_shade(paths, "", kThroughput, 1);
    CHECK(seen.survived > 0);
    CHECK(seen.ended > 0);
    CHECK(seen.transmitted > 0);
    CHECK(seen.reflected > 0);
}

TEST_CASE("roulette: Cycles' rule, min(1, sqrt(max(throughput))), against a host model",
          "[cl][shade][roulette]") {
    const std::vector<PathIn> paths = roulette_paths();
    const Seen seen = check_shade(paths, "-D WP_ROULETTE_RULE=2", kSqrt, 1);
    CHECK(seen.survived > 0);
    CHECK(seen.ended > 0);
    CHECK(seen.below_one > 0);
}

TEST_CASE("roulette: the relative rule, the throughput over the first bounce's, carried in "
          "throughput.w, against a host model",
          "[cl][shade][roulette]") {
    const std::vector<PathIn> paths = roulette_paths();
    // From bounce 1 the first bounce always goes on (the ratio is 1); from
    // bounce 3 on it is the later bounces' share that decides.
    const Seen seen = check_shade(paths, "-D WP_ROULETTE_RULE=3", kRelative, 1);
    CHECK(seen.survived > 0);
    CHECK(seen.ended > 0);
    CHECK(seen.below_one > 0);
    CHECK(seen.transmitted > 0);
}
