// Stage 2, intersect: closest hits against a double-precision reference
// (Moller-Trumbore for triangles, the plain quadratic for spheres).
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct RefTriangle {
    D3 v0, v1, v2;
};

struct RefSphere {
    D3 center;
    double radius;
};

// The scene as the device sees it (float32), read back into doubles.
struct RefScene {
    std::vector<RefTriangle> triangles;
    std::vector<RefSphere> spheres;
};

// Ray/triangle in double (Moller-Trumbore, both faces): t > 0 or +inf.
double hit_triangle(const D3& o, const D3& d, const RefTriangle& tri) {
    D3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    D3 p = cross(d, e2);
    double det = dot(e1, p);
    if (det == 0.0)
        return kInf;
    D3 s = o - tri.v0;
    double u = dot(s, p) / det;
    if (u < 0.0 || u > 1.0)
        return kInf;
    D3 q = cross(s, e1);
    double v = dot(d, q) / det;
    if (v < 0.0 || u + v > 1.0)
        return kInf;
    double t = dot(e2, q) / det;
    return t > 0.0 ? t : kInf;
}

// Ray/sphere in double: the nearest root with t > 0, or +inf.
double hit_sphere(const D3& o, const D3& d, const RefSphere& s) {
    D3 f = o - s.center;
    double a = dot(d, d), half_b = dot(f, d), c = dot(f, f) - s.radius * s.radius;
    double discriminant = half_b * half_b - a * c;
    if (discriminant < 0.0)
        return kInf;
    double root = std::sqrt(discriminant);
    double t0 = (-half_b - root) / a, t1 = (-half_b + root) / a;
    if (t0 > 0.0)
        return t0;
    return t1 > 0.0 ? t1 : kInf;
}

struct RefHit {
    double t = kInf;
    cl_uint primitive = WP_NO_HIT;
    double second_t = kInf; // the next-closest hit of another primitive
};

// Primitives are numbered triangles first, then spheres; ties go to the lower number.
RefHit reference_hit(const RefScene& scene, const D3& o, const D3& d) {
    RefHit best;
    auto consider = [&](double t, cl_uint id) {
        if (t < best.t) {
            best.second_t = best.t;
            best.t = t;
            best.primitive = id;
        } else if (t < best.second_t) {
            best.second_t = t;
        }
    };
    for (std::size_t i = 0; i < scene.triangles.size(); ++i)
        consider(hit_triangle(o, d, scene.triangles[i]), cl_uint(i));
    for (std::size_t i = 0; i < scene.spheres.size(); ++i)
        consider(hit_sphere(o, d, scene.spheres[i]), cl_uint(scene.triangles.size() + i));
    return best;
}

struct DeviceGeometry {
    std::vector<WpTriangle> triangles;
    std::vector<WpSphere> spheres;
    RefScene reference;

    void add_triangle(const D3& a, const D3& b, const D3& c) {
        WpTriangle t{};
        t.v0 = to_float4(a);
        t.v1 = to_float4(b);
        t.v2 = to_float4(c);
        triangles.push_back(t);
        reference.triangles.push_back({from_float4(t.v0), from_float4(t.v1), from_float4(t.v2)});
    }
    void add_sphere(const D3& center, double radius) {
        WpSphere s{};
        s.center_radius = to_float4(center, radius);
        spheres.push_back(s);
        reference.spheres.push_back({from_float4(s.center_radius), double(s.center_radius.s[3])});
    }
};

struct IntersectResult {
    std::vector<cl_float> t;
    std::vector<cl_uint> primitive;
};

constexpr cl_float kSentinelT = -3.0f;
constexpr cl_uint kSentinelPrimitive = 0x5a5a5a5au;

// Intersects the rays listed in queue[0, ray_count), with the queue's length
// in counters[ray_counter] as the wavefront loop keeps it; every other counter
// holds more than the queue, so reading the wrong one would trace the entries
// past ray_count. The launch covers every entry of the queue buffer, as the
// host launches for the most the queue can hold. Every slot's outputs start
// out as sentinels.
IntersectResult run_intersect(const DeviceGeometry& geometry, const std::vector<cl_float4>& origins,
                              const std::vector<cl_float4>& directions,
                              const std::vector<cl_uint>& queue, cl_uint ray_count,
                              cl_uint ray_counter, const std::string& options = "") {
    WpFrame frame{};
    frame.triangle_count = cl_uint(geometry.triangles.size());
    frame.sphere_count = cl_uint(geometry.spheres.size());
    const std::size_t slots = origins.size();
    std::vector<cl_uint> counters(WP_COUNTER_COUNT, cl_uint(queue.size()));
    counters[ray_counter] = ray_count;
    // The two ray queues, `queue` as queue `ray_counter` and the other full of
    // slot 0, so that reading the wrong one would leave sentinels behind.
    frame.pool_size = cl_uint(queue.size());
    std::vector<cl_uint> queues(2 * queue.size(), 0u);
    std::copy(queue.begin(), queue.end(),
              queues.begin() + std::ptrdiff_t(ray_counter * queue.size()));
    DeviceBuffers buffers = stage_buffers(slots, 1);
    buffers.ray_queues = upload(queues);
    buffers.counters = upload(counters);
    buffers.ray_origin = upload(origins);
    buffers.ray_direction = upload(directions);
    buffers.triangles = upload(geometry.triangles);
    buffers.spheres = upload(geometry.spheres);
    buffers.hit_t = upload(std::vector<cl_float>(slots, kSentinelT));
    buffers.hit_primitive = upload(std::vector<cl_uint>(slots, kSentinelPrimitive));
    run_stage("intersect", frame, make_launch(0, ray_counter), buffers, queue.size(), options);
    // The counters are read, never written.
    CHECK(download<cl_uint>(buffers.counters, WP_COUNTER_COUNT) == counters);
    return {download<cl_float>(buffers.hit_t, slots),
            download<cl_uint>(buffers.hit_primitive, slots)};
}

} // namespace

TEST_CASE("intersect: hand-made rays find the closest primitive and its distance",
          "[cl][intersect]") {
    DeviceGeometry g;
    g.add_triangle({-4, -4, -5}, {4, -4, -5}, {0, 4, -5});    // 0: a wall across -z
    g.add_triangle({10, -1, -1}, {10, 1, -1}, {10, 0, 1});    // 1: at x = 10 ...
    g.add_triangle({10, -1, -1}, {10, 1, -1}, {10, 0, 1});    // 2: ... and the same again
    g.add_triangle({-10, -1, -1}, {-10, 0, 1}, {-10, 1, -1}); // 3: at x = -10
    g.add_sphere({0, 5, -5}, 1.5);                            // 4
    g.add_sphere({0, 0, -3}, 0.5);                            // 5: in front of the wall
    g.add_sphere({2, -2, -8}, 1.0);                           // 6: behind the wall

    struct Case {
        const char* what;
        D3 origin, direction;
        cl_uint expected;
    };
    const Case cases[] = {
        {"triangle only", {0, 0, 0}, normalize(D3(-1, -3, -5)), 0},
        {"sphere only", {0, 0, 0}, normalize(D3(0, 5, -5)), 4},
        {"sphere in front of a triangle", {0, 0, 0}, {0, 0, -1}, 5},
        {"triangle in front of a sphere", {0, 0, 0}, normalize(D3(2, -2, -8)), 0},
        {"miss, parallel to the wall", {0, 0, 0}, {0, 1, 0}, WP_NO_HIT},
        {"miss, everything behind", {0, 0, 0}, {0, 0, 1}, WP_NO_HIT},
        {"from inside a sphere", {0, 5.3, -5}, {1, 0, 0}, 4},
        {"exact tie of coincident triangles", {0, 0, 0}, normalize(D3(10, 0, -0.3)), 1},
        {"back face of a triangle", {0, 0, 0}, normalize(D3(-1, 0, -0.03)), 3},
        {"direction of length 2", {0, 0, 0}, {0, 0, -2}, 5},
        {"sphere behind the origin", {0, 0, -3.6}, {0, 0, -1}, 0},
        {"passing just outside a sphere", {0, 0.6, 0}, {0, 0, -1}, 0},
    };
    const std::size_t n = std::size(cases);

    // One extra slot that is in the queue buffer but past the queue's length.
    std::vector<cl_float4> origins, directions;
    for (const Case& c : cases) {
        origins.push_back(to_float4(c.origin));
        directions.push_back(to_float4(c.direction));
    }
    origins.push_back(float4(0, 0, 0));
    directions.push_back(float4(0, 0, -1));
    std::vector<cl_uint> queue;
    for (std::size_t i = n; i-- > 0;)
        queue.push_back(cl_uint(i)); // reversed: results go by slot, not by queue position
    queue.push_back(cl_uint(n));
    // With the runtime counts and with the counts compiled in, whose kernel
    // PoCL vectorises and whose surplus work-items trace slot 0's ray without
    // storing anything (kernels/traverse.h, WP_TRACE_SURPLUS_ITEMS).
    const std::string fixed_counts = "-D WP_TRIANGLE_COUNT=" + std::to_string(g.triangles.size()) +
                                     " -D WP_SPHERE_COUNT=" + std::to_string(g.spheres.size());
    for (const std::string& options : {std::string(), fixed_counts}) {
        INFO("build options: '" << options << "'");
        IntersectResult r =
            run_intersect(g, origins, directions, queue, cl_uint(n), WP_COUNTER_QUEUE_B, options);

        for (std::size_t i = 0; i < n; ++i) {
            const Case& c = cases[i];
            INFO(c.what);
            D3 o = from_float4(origins[i]), d = from_float4(directions[i]);
            RefHit ref = reference_hit(g.reference, o, d);
            REQUIRE(ref.primitive == c.expected); // the reference agrees with the hand-made answer
            CHECK(r.primitive[i] == c.expected);
            if (c.expected == WP_NO_HIT) {
                CHECK(std::isinf(r.t[i]));
                CHECK(r.t[i] > 0.0f);
            } else {
                INFO("device t " << r.t[i] << " reference t " << ref.t);
                CHECK(std::fabs(r.t[i] - ref.t) <= 1e-5 * ref.t);
            }
        }
        // Hand-computed distances, as a check on the reference itself.
        CHECK(std::fabs(r.t[2] - 2.5) < 1e-6);
        CHECK(std::fabs(r.t[6] - std::sqrt(1.5 * 1.5 - 0.3 * 0.3)) < 1e-5);
        CHECK(std::fabs(r.t[9] - 1.25) < 1e-6);
        CHECK(std::fabs(r.t[11] - 5.0) < 1e-5);
        // The slot past the queue's length is untouched.
        CHECK(r.t[n] == kSentinelT);
        CHECK(r.primitive[n] == kSentinelPrimitive);

        // An empty queue traces nothing, however many work-items run.
        IntersectResult none =
            run_intersect(g, origins, directions, queue, 0, WP_COUNTER_QUEUE_A, options);
        for (std::size_t i = 0; i <= n; ++i) {
            INFO("slot " << i);
            CHECK(none.t[i] == kSentinelT);
            CHECK(none.primitive[i] == kSentinelPrimitive);
        }
    }
}

TEST_CASE("intersect: random rays agree with the double-precision reference", "[cl][intersect]") {
    std::mt19937 generator(12345u);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::normal_distribution<double> normal(0.0, 1.0);
    auto point = [&](double scale) {
        return D3(scale * uniform(generator), scale * uniform(generator),
                  scale * uniform(generator));
    };

    DeviceGeometry g;
    for (int i = 0; i < 20; ++i) {
        D3 centre = point(1.5);
        g.add_triangle(centre + point(1.5), centre + point(1.5), centre + point(1.5));
    }
    for (int i = 0; i < 4; ++i)
        g.add_sphere(point(1.5), 0.1 + 0.4 * (0.5 + 0.5 * uniform(generator)));

    const std::size_t n = 10000;
    std::vector<cl_float4> origins, directions;
    std::vector<cl_uint> queue;
    for (std::size_t i = 0; i < n; ++i) {
        origins.push_back(to_float4(point(1.0)));
        directions.push_back(
            to_float4(normalize(D3(normal(generator), normal(generator), normal(generator)))));
        queue.push_back(cl_uint(i));
    }
    IntersectResult r =
        run_intersect(g, origins, directions, queue, cl_uint(n), WP_COUNTER_QUEUE_A);

    std::size_t hits = 0, near_ties = 0, mismatches = 0, t_errors = 0;
    double worst_t = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        D3 o = from_float4(origins[i]), d = from_float4(directions[i]);
        RefHit ref = reference_hit(g.reference, o, d);
        if (ref.primitive != WP_NO_HIT)
            ++hits;
        bool near_tie = ref.second_t - ref.t <= 1e-4 * ref.t;
        if (near_tie) {
            ++near_ties;
            continue;
        }
        if (r.primitive[i] != ref.primitive) {
            if (mismatches++ < 5) {
                INFO("ray " << i << ": device " << r.primitive[i] << " at " << r.t[i]
                            << ", reference " << ref.primitive << " at " << ref.t);
                CHECK(r.primitive[i] == ref.primitive);
            }
            continue;
        }
        if (ref.primitive == WP_NO_HIT) {
            if (!(std::isinf(r.t[i]) && r.t[i] > 0.0f) && t_errors++ < 5) {
                INFO("ray " << i << " missed with t " << r.t[i]);
                CHECK(std::isinf(r.t[i]));
            }
            continue;
        }
        // Relative to the distance, plus the origin's magnitude for hits very close to it.
        double error = std::fabs(r.t[i] - ref.t) / (ref.t + max_abs(o));
        worst_t = std::max(worst_t, error);
        if (error > 1e-5 && t_errors++ < 5) {
            INFO("ray " << i << ": device t " << r.t[i] << ", reference t " << ref.t);
            CHECK(error <= 1e-5);
        }
    }
    INFO(hits << " hits, " << near_ties << " near ties, worst relative t error " << worst_t);
    CHECK(hits > n / 2); // the batch exercises hits as well as misses
    CHECK(near_ties < n / 100);
    CHECK(mismatches == 0);
    CHECK(t_errors == 0);
}

TEST_CASE("intersect: rays through the shared edges and vertex of a fan never slip through",
          "[cl][intersect]") {
    // Six triangles around a shared centre vertex, on a tilted plane.
    const D3 centre(0.1, 0.2, -3.0);
    const D3 u = normalize(D3(1.0, 0.1, 0.3)), v = normalize(cross(D3(0.2, 0.1, 1.0), u));
    std::vector<D3> rim;
    for (int i = 0; i < 6; ++i) {
        double angle = 2.0 * M_PI * i / 6.0 + 0.3 * std::sin(i); // uneven spokes
        rim.push_back(centre + 1.5 * std::cos(angle) * u + 1.5 * std::sin(angle) * v);
    }
    DeviceGeometry g;
    for (int i = 0; i < 6; ++i)
        g.add_triangle(centre, rim[i], rim[(i + 1) % 6]);
    const D3 centre_f = from_float4(g.triangles[0].v0); // the shared vertex as stored
    std::vector<D3> rim_f;
    for (const WpTriangle& t : g.triangles)
        rim_f.push_back(from_float4(t.v1));

    // Rays from random origins towards points on the spokes (each shared by two
    // triangles) and towards the centre vertex (shared by all six).
    std::mt19937 generator(777u);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<cl_float4> origins, directions;
    std::vector<cl_uint> queue;
    for (int i = 0; i < 6000; ++i) {
        D3 origin(4.0 * uniform(generator) - 2.0, 4.0 * uniform(generator) - 2.0,
                  2.0 * uniform(generator));
        D3 target = i % 10 == 0
                        ? centre_f
                        : centre_f + (0.02 + 0.9 * uniform(generator)) * (rim_f[i % 6] - centre_f);
        queue.push_back(cl_uint(origins.size()));
        origins.push_back(to_float4(origin));
        directions.push_back(to_float4(normalize(target - origin)));
    }
    IntersectResult r =
        run_intersect(g, origins, directions, queue, cl_uint(queue.size()), WP_COUNTER_QUEUE_B);
    std::size_t misses = 0, bad_t = 0;
    for (std::size_t i = 0; i < origins.size(); ++i) {
        if (r.primitive[i] == WP_NO_HIT) {
            ++misses;
            continue;
        }
        // The hit lies on the fan's plane, near the aimed-at point.
        D3 hit = from_float4(origins[i]) + double(r.t[i]) * from_float4(directions[i]);
        bad_t += std::fabs(dot(hit - centre_f, normalize(cross(u, v)))) > 1e-5;
    }
    CHECK(misses == 0);
    CHECK(bad_t == 0);
}
