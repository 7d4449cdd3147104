// A hierarchy leaf's triangles tested four at a time (kernels/triangle4.h)
// against testing them one at a time in order (wp_triangle_test with a
// shrinking bound, the loop the four-lane test replaced), both run by one
// kernel on the same rays and leaves: the closest hit must be the same
// triangle at the same t bit for bit, and any-hit the same (first) triangle.
// Leaves of 1 to 9 triangles (so full groups of four, tails and lanes past
// the end), with shared edges, duplicates (exact ties, which the loop's
// shrinking bound may give to either copy: the four-lane test must pick the same one), degenerate
// triangles (repeated and collinear corners) and rays aimed at interiors, edges and vertices, with
// infinite and finite bounds. The closest hits are also held against a double-precision host
// reference: the reported t is the ray's distance to that triangle's plane. The any-hit leaf test
// of the shadow rays' traversal (wp_leaf_triangles_occluded) must say hit exactly where the loop
// finds a first hit.
#include "support/kernel_test_util.hpp"

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

const char* kLeafSource = R"CLC(
#include "triangle4.h"

/* Ray i: origin xyz with bound w, direction xyz; its leaf is
 * triangles[leaves[i].x .. leaves[i].x + leaves[i].y - 1]. */
__kernel void leaf(__global const WpTriangle* triangles, __global const uint2* leaves,
                   wp_uint count, __global const float4* origins,
                   __global const float4* directions, __global wp_uint* hits_out,
                   __global float* t_out) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    float3 o = origins[i].xyz, d = directions[i].xyz;
    float t_max = origins[i].w;
    wp_uint first = leaves[i].x, n = leaves[i].y;
    WpShearedRay ray = wp_shear_ray(o, d);

    /* One at a time, in order: the closest hit and the first hit. */
    float closest = t_max;
    wp_uint hit = WP_NO_HIT, first_hit = WP_NO_HIT;
    for (wp_uint k = first; k < first + n; ++k) {
        __global const WpTriangle* t = &triangles[k];
        float tk;
        if (wp_intersect_triangle(&ray, t->v0.xyz, t->v1.xyz, t->v2.xyz, closest, &tk)) {
            closest = tk;
            hit = k;
        }
        if (first_hit == WP_NO_HIT &&
            wp_intersect_triangle(&ray, t->v0.xyz, t->v1.xyz, t->v2.xyz, t_max, &tk))
            first_hit = k;
    }
    float four_closest = t_max, four_any = t_max;
    wp_uint four_hit = wp_leaf_triangles(triangles, first, n, &ray, 0, &four_closest);
    wp_uint four_first = wp_leaf_triangles(triangles, first, n, &ray, 1, &four_any);
    hits_out[5 * i + 0] = hit;
    hits_out[5 * i + 1] = four_hit;
    hits_out[5 * i + 2] = first_hit;
    hits_out[5 * i + 3] = four_first;
    hits_out[5 * i + 4] = wp_leaf_triangles_occluded(triangles, first, n, &ray, t_max);
    t_out[2 * i + 0] = closest;
    t_out[2 * i + 1] = four_closest;
}
)CLC";

struct Corner {
    double x, y, z;
};

cl_float4 f4(const Corner& c, float w = 0.0f) {
    return float4(float(c.x), float(c.y), float(c.z), w);
}

Corner mix(const Corner& a, const Corner& b, const Corner& c, double u, double v) {
    double w = 1.0 - u - v;
    return {w * a.x + u * b.x + v * c.x, w * a.y + u * b.y + v * c.y, w * a.z + u * b.z + v * c.z};
}

Corner corner(const cl_float4& v) {
    return {v.s[0], v.s[1], v.s[2]};
}

// The distance along (o, d) to the plane of triangle t, in double.
double plane_distance(const WpTriangle& t, const Corner& o, const Corner& d) {
    Corner a = corner(t.v0), b = corner(t.v1), c = corner(t.v2);
    Corner e1{b.x - a.x, b.y - a.y, b.z - a.z}, e2{c.x - a.x, c.y - a.y, c.z - a.z};
    Corner n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    double along = n.x * d.x + n.y * d.y + n.z * d.z;
    return (n.x * (a.x - o.x) + n.y * (a.y - o.y) + n.z * (a.z - o.z)) / along;
}

} // namespace

TEST_CASE("leaf triangles: four at a time give the one-at-a-time test's hits bit for bit, on "
          "20,000 rays through leaves with shared edges, ties and degenerate triangles",
          "[cl][bvh]") {
    std::mt19937 rng(35);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto point = [&](double scale) {
        return Corner{scale * (2.0 * unit(rng) - 1.0), scale * (2.0 * unit(rng) - 1.0),
                      scale * (2.0 * unit(rng) - 1.0)};
    };

    std::vector<WpTriangle> triangles;
    std::vector<bool> degenerate; // per triangle: no plane to measure against
    std::vector<bool> grazing;    // per ray: starts in its target's plane
    std::vector<cl_uint2> leaves;
    std::vector<cl_float4> origins, directions;
    const int leaf_count = 2500, rays_per_leaf = 8;
    for (int l = 0; l < leaf_count; ++l) {
        cl_uint first = cl_uint(triangles.size());
        cl_uint n = 1 + cl_uint(l % 9);
        for (cl_uint k = 0; k < n; ++k) {
            Corner a = point(1.0), b = point(1.0), c = point(1.0);
            std::uint32_t kind = std::uint32_t(rng() % 8);
            if (k > 0 && kind == 0) { // a duplicate of the one before: an exact tie
                triangles.push_back(triangles.back());
                degenerate.push_back(degenerate.back());
                continue;
            }
            if (k > 0 && kind == 1) { // shares the edge v1-v2 of the one before
                const WpTriangle& p = triangles.back();
                a = corner(p.v2), b = corner(p.v1);
            }
            if (kind == 2) // degenerate: a repeated corner
                c = b;
            if (kind == 3) // degenerate: collinear corners
                c = mix(a, b, b, 0.25, 0.5);
            triangles.push_back(WpTriangle{f4(a), f4(b), f4(c)});
            degenerate.push_back(kind == 2 || kind == 3);
        }
        for (int r = 0; r < rays_per_leaf; ++r) {
            const WpTriangle& aim = triangles[first + cl_uint(rng() % n)];
            double u = unit(rng), v = unit(rng);
            if (u + v > 1.0)
                u = 1.0 - u, v = 1.0 - v;
            switch (rng() % 4) {
            case 0: // on an edge
                v = 0.0;
                break;
            case 1: // on a vertex
                u = v = 0.0;
                break;
            default: // inside
                break;
            }
            Corner target = mix(corner(aim.v0), corner(aim.v1), corner(aim.v2), u, v);
            Corner o = point(3.0);
            if (r == rays_per_leaf - 1) // parallel to the aimed triangle's plane
                o = mix(corner(aim.v0), corner(aim.v1), corner(aim.v2), -1.0, 0.5);
            Corner d{target.x - o.x, target.y - o.y, target.z - o.z};
            // Bounds: none, past the target, and short of it.
            float t_max = r % 3 == 0 ? INFINITY : float(r % 3 == 1 ? 1.5 : 0.999);
            leaves.push_back(cl_uint2{{first, n}});
            grazing.push_back(r == rays_per_leaf - 1);
            origins.push_back(f4(o, t_max));
            directions.push_back(f4(d));
        }
    }

    const std::size_t count = origins.size();
    cl::Kernel kernel(program(kLeafSource, "leaf_triangles.cl"), "leaf");
    cl::Buffer triangle_buffer = upload(triangles), leaf_buffer = upload(leaves),
               origin_buffer = upload(origins), direction_buffer = upload(directions);
    cl::Buffer hits = upload(std::vector<cl_uint>(5 * count)),
               ts = upload(std::vector<float>(2 * count));
    set_args(kernel, triangle_buffer, leaf_buffer, cl_uint(count), origin_buffer, direction_buffer,
             hits, ts);
    launch(kernel, count);
    std::vector<cl_uint> hit = download<cl_uint>(hits, 5 * count);
    std::vector<float> t = download<float>(ts, 2 * count);

    std::size_t closest_hits = 0, any_hits = 0, ties = 0, differ = 0, any_differ = 0,
                occluded_differ = 0, far_from_plane = 0;
    for (std::size_t i = 0; i < count; ++i) {
        if (hit[5 * i] != hit[5 * i + 1] || float_bits(t[2 * i]) != float_bits(t[2 * i + 1]))
            ++differ;
        if (hit[5 * i + 2] != hit[5 * i + 3])
            ++any_differ;
        if ((hit[5 * i + 2] != WP_NO_HIT) != (hit[5 * i + 4] != 0))
            ++occluded_differ;
        if (hit[5 * i] == WP_NO_HIT)
            continue;
        ++closest_hits;
        any_hits += hit[5 * i + 2] != WP_NO_HIT;
        // A duplicate ahead of the hit (a tie the loop gave to the later copy).
        if (hit[5 * i] > leaves[i].s[0] &&
            std::memcmp(&triangles[hit[5 * i]], &triangles[hit[5 * i] - 1], sizeof(WpTriangle)) ==
                0)
            ++ties;
        if (degenerate[hit[5 * i]] || grazing[i])
            continue;
        Corner o = corner(origins[i]), d = corner(directions[i]);
        double reference = plane_distance(triangles[hit[5 * i]], o, d);
        if (!(std::abs(double(t[2 * i]) - reference) <= 1.0e-4 * std::max(1.0, reference)))
            ++far_from_plane;
    }
    INFO("rays " << count << ", closest hits " << closest_hits << ", any hits " << any_hits);
    CHECK(differ == 0);
    CHECK(any_differ == 0);
    CHECK(occluded_differ == 0);
    CHECK(ties > 0); // the ties were exercised
    CHECK(far_from_plane == 0);
    // The rays must exercise both outcomes (all are aimed at a triangle; the
    // bounds short of it, degenerate targets and grazing rays miss).
    CHECK(closest_hits > count / 3);
    CHECK(closest_hits < count);
    CHECK(any_hits == closest_hits);
}
