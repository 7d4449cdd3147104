/* The ray-triangle test, in float32: the watertight test of Woop, Benthin
 * and Wald (JCGT 2013). The ray is sheared so it runs along +z, and each edge
 * function is computed from the two vertices of that edge alone. Two
 * triangles sharing an edge compute exactly negated edge values
 * (multiplication commutes and subtraction is exactly antisymmetric, as long
 * as the compiler does not contract a*b - c*d into an FMA, hence FP_CONTRACT
 * OFF in wp_shared.h), so a ray can never slip between them.
 *
 * (The Moller-Trumbore test it replaced, which lets rays through shared
 * edges, lives on in the stability tests only: tests/stability/naive.hpp.)
 */
#ifndef WP_TRIANGLE_H
#define WP_TRIANGLE_H

#include "wp_shared.h"

/* How far outside the box of a triangle's projected corners a ray may pass
 * and still hit it, relative to the corners' distance from the ray origin:
 * about 8 float ulps, above the rounding of the sheared coordinates. */
#define WP_SLIVER_GUARD_RELATIVE 1.0e-6f

/* The test is written on scalars, not float3, so that PoCL can vectorise
 * the traversal loop across work-items (one ray per SIMD lane): LLVM's loop
 * vectoriser gives up on a loop body that holds any vector-typed
 * instruction (docs/specialization.md). For the same reason, lines that do
 * alike work on different operands are written in different ways where the
 * SLP vectoriser would otherwise pack them into short vectors. */

/* The larger and the smaller of two floats as one compare and select (on
 * x86 one maxps or minps), where OpenCL's fmax and fmin must also return the
 * number when the other operand is a NaN (a compare, a max and a blend). The
 * sliver guard below needs no such care: for numbers both give the same
 * value (up to a zero's sign, which only comparisons see, and they see
 * -0 == +0). Only a NaN corner coordinate, which comes from a NaN ray (or a
 * zero direction), can make them differ, and for such a ray the edge values
 * are NaN and the decision was never meaningful: a path that met one
 * carries a NaN sample, which the film drops and counts (accumulate.cl). */
static inline float wp_max(float a, float b) {
    return a > b ? a : b;
}
static inline float wp_min(float a, float b) {
    return a < b ? a : b;
}

/* Component `axis` (0, 1, 2 for x, y, z) of (x, y, z): selects, not an
 * index. The three forms give the same value; each axis of the sheared frame
 * uses its own, so that SLP finds no two alike selects to pack. */
static inline float wp_axis(float x, float y, float z, int axis) {
    return axis == 0 ? x : (axis == 1 ? y : z);
}
static inline float wp_axis_from_z(float x, float y, float z, int axis) {
    return axis == 2 ? z : (axis == 1 ? y : x);
}
static inline float wp_axis_from_y(float x, float y, float z, int axis) {
    return axis == 1 ? y : (axis == 0 ? x : z);
}

/* What the watertight test needs of a ray, computed once per ray: the axis
 * permutation, the origin's components on those axes, and the shear. */
typedef struct {
    int kx, ky, kz;   /* kz: the direction's dominant axis */
    float ox, oy, oz; /* the origin's components on axes kx, ky, kz */
    float dx, dy, dz; /* the direction's */
    float sx, sy, sz;
} WpShearedRay;

static inline WpShearedRay wp_shear_ray_xyz(float ox, float oy, float oz, float dx, float dy,
                                            float dz) {
    WpShearedRay r;
    /* Three different forms of |d|, all exact, so that SLP does not pack them. */
    float ax = fabs(dx);
    float ay = dy < 0.0f ? -dy : dy;
    float az = fmax(dz, -dz);
    r.kz = (ax > ay) ? ((ax > az) ? 0 : 2) : ((ay > az) ? 1 : 2);
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    float d_z = wp_axis(dx, dy, dz, r.kz);
    if (d_z < 0.0f) { /* keep the winding: swap the other two axes */
        int k = r.kx;
        r.kx = r.ky;
        r.ky = k;
    }
    r.sx = wp_axis_from_z(dx, dy, dz, r.kx) / d_z;
    r.sy = wp_axis_from_y(dx, dy, dz, r.ky) / d_z;
    r.sz = 1.0f / d_z;
    r.ox = wp_axis_from_z(ox, oy, oz, r.kx);
    r.oy = wp_axis_from_y(ox, oy, oz, r.ky);
    r.oz = wp_axis(ox, oy, oz, r.kz);
    r.dx = wp_axis_from_z(dx, dy, dz, r.kx);
    r.dy = wp_axis_from_y(dx, dy, dz, r.ky);
    r.dz = d_z;
    return r;
}

static inline WpShearedRay wp_shear_ray(float3 origin, float3 direction) {
    return wp_shear_ray_xyz(origin.x, origin.y, origin.z, direction.x, direction.y, direction.z);
}

/* 1 if the scaled distance T over det (the sum of the edge values, 0 when
 * the ray lies in the triangle's plane) is a t with 0 < t < t_max, tested
 * without dividing. For a fixed T and det it can only turn from 1 to 0 as
 * t_max shrinks (t_max * det rounds monotonically), which is what lets the
 * four-lane leaf test (triangle4.h) test against the bound it entered the
 * leaf with first and against the shrinking one after. */
static inline int wp_triangle_in_range(float T, float det, float t_max) {
    return det > 0.0f ? !(T <= 0.0f || T >= t_max * det)
                      : (det != 0.0f && !(T >= 0.0f || T <= t_max * det));
}

/* Returns 1 if the ray hits the triangle (p0, p1, p2) at 0 < t < t_max, and
 * sets *t to that t either way (meaningless on a miss), so that a loop can
 * select rather than branch. Both faces are hit; points on an edge or vertex
 * count as inside. A component is picked before the origin is subtracted
 * ((p - o)[k] == p[k] - o[k] exactly), so nothing here is a vector. */
static inline int wp_triangle_test(const WpShearedRay* ray, float p0x, float p0y, float p0z,
                                   float p1x, float p1y, float p1z, float p2x, float p2y, float p2z,
                                   float t_max, float* t) {
    int kx = ray->kx, ky = ray->ky, kz = ray->kz;
    float az = wp_axis(p0x, p0y, p0z, kz) - ray->oz;
    float bz = wp_axis(p1x, p1y, p1z, kz) - ray->oz;
    float cz = wp_axis(p2x, p2y, p2z, kz) - ray->oz;
    float a_x = wp_axis_from_z(p0x, p0y, p0z, kx) - ray->ox;
    float a_y = wp_axis_from_y(p0x, p0y, p0z, ky) - ray->oy;
    float b_x = wp_axis_from_z(p1x, p1y, p1z, kx) - ray->ox;
    float b_y = wp_axis_from_y(p1x, p1y, p1z, ky) - ray->oy;
    float c_x = wp_axis_from_z(p2x, p2y, p2z, kx) - ray->ox;
    float c_y = wp_axis_from_y(p2x, p2y, p2z, ky) - ray->oy;
    float ax = a_x - ray->sx * az;
    float ay = a_y - ray->sy * az;
    float bx = b_x - ray->sx * bz;
    float by = b_y - ray->sy * bz;
    float cx = c_x - ray->sx * cz;
    float cy = c_y - ray->sy * cz;

    float u = cx * by - cy * bx; /* edge p1-p2 */
    float v = ax * cy - ay * cx; /* edge p2-p0 */
    float w = bx * ay - by * ax; /* edge p0-p1 */
    int inside = !((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f));
    /* A ray within about 1e-7 rad of the triangle's plane sees it as a sliver
     * thinner than the rounding of the sheared corners, and the edge values'
     * signs become noise: they could accept a ray passing far beside the
     * triangle (docs/stability.md, case 10). The ray's point (0, 0) must at
     * least lie in the box of the three projected corners, widened by their
     * rounding. A point the exact edge tests would accept always does, so
     * this rejects only wrong decisions, and it keeps the test watertight:
     * a ray through a shared edge or vertex lies in both triangles' boxes.
     *
     * The corners' largest coordinate, as one chain of maxima (exact and
     * order-free, so the axis order does not matter; max(x, -x) = |x|),
     * each link depending on the last, so that SLP finds no two alike
     * operations side by side. A zero's sign may differ from fabs's, which
     * only comparisons see. */
    float m = wp_max(a_x, -a_x);
    m = wp_max(wp_max(m, a_y), -a_y);
    m = wp_max(wp_max(m, az), -az);
    m = wp_max(wp_max(m, b_x), -b_x);
    m = wp_max(wp_max(m, b_y), -b_y);
    m = wp_max(wp_max(m, bz), -bz);
    m = wp_max(wp_max(m, c_x), -c_x);
    m = wp_max(wp_max(m, c_y), -c_y);
    m = wp_max(wp_max(m, cz), -cz);
    float slack = WP_SLIVER_GUARD_RELATIVE * m;
    /* The box's sides, as chains from an infinite start (min(inf, x) == x)
     * for the same reason: equal to min(min(ax, bx), cx) and so on. */
    float low_x = wp_min(wp_min(wp_min(INFINITY, ax), bx), cx);
    float high_x = wp_max(wp_max(wp_max(-INFINITY, ax), bx), cx);
    float low_y = wp_min(wp_min(wp_min(INFINITY, ay), by), cy);
    float high_y = wp_max(wp_max(wp_max(-INFINITY, ay), by), cy);
    int in_box = !(low_x > slack || high_x < -slack || low_y > slack || high_y < -slack);
    float det = u + v + w; /* 0: the ray lies in the triangle's plane */

    /* Scaled distance: t = T / det, tested without dividing. */
    float T = u * (ray->sz * az) + v * (ray->sz * bz) + w * (ray->sz * cz);
    *t = T / det;
    return inside && in_box && wp_triangle_in_range(T, det, t_max);
}

/* Returns 1 and sets *t if the ray hits the triangle at 0 < t < t_max. */
static inline int wp_intersect_triangle(const WpShearedRay* ray, float3 p0, float3 p1, float3 p2,
                                        float t_max, float* t) {
    float t_test;
    int hit =
        wp_triangle_test(ray, p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z, t_max, &t_test);
    if (hit)
        *t = t_test;
    return hit;
}

/* Unnormalised front-face normal of a triangle. */
static inline float3 wp_triangle_normal(const WpTriangle* tri) {
    return cross(tri->v1.xyz - tri->v0.xyz, tri->v2.xyz - tri->v0.xyz);
}

#endif /* WP_TRIANGLE_H */
