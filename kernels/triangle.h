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

#include "ray_offset.h" /* wp_max_abs_component */

/* How far outside the box of a triangle's projected corners a ray may pass
 * and still hit it, relative to the corners' distance from the ray origin:
 * about 8 float ulps, above the rounding of the sheared coordinates. */
#define WP_SLIVER_GUARD_RELATIVE 1.0e-6f

static inline float wp_axis(float3 v, int axis) {
    return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

/* What the watertight test needs of a ray, computed once per ray. */
typedef struct {
    float3 origin;
    int kx, ky, kz; /* kz: the direction's dominant axis */
    float sx, sy, sz;
} WpShearedRay;

static inline WpShearedRay wp_shear_ray(float3 origin, float3 direction) {
    WpShearedRay r;
    float3 a = fabs(direction);
    r.kz = (a.x > a.y) ? ((a.x > a.z) ? 0 : 2) : ((a.y > a.z) ? 1 : 2);
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    float dz = wp_axis(direction, r.kz);
    if (dz < 0.0f) { /* keep the winding: swap the other two axes */
        int k = r.kx;
        r.kx = r.ky;
        r.ky = k;
    }
    r.sx = wp_axis(direction, r.kx) / dz;
    r.sy = wp_axis(direction, r.ky) / dz;
    r.sz = 1.0f / dz;
    r.origin = origin;
    return r;
}

/* Returns 1 and sets *t if the ray hits the triangle at 0 < t < t_max.
 * Both faces are hit; points on an edge or vertex count as inside. */
static inline int wp_intersect_triangle(const WpShearedRay* ray, float3 p0, float3 p1, float3 p2,
                                        float t_max, float* t) {
    float3 a = p0 - ray->origin;
    float3 b = p1 - ray->origin;
    float3 c = p2 - ray->origin;
    float az = wp_axis(a, ray->kz), bz = wp_axis(b, ray->kz), cz = wp_axis(c, ray->kz);
    float ax = wp_axis(a, ray->kx) - ray->sx * az;
    float ay = wp_axis(a, ray->ky) - ray->sy * az;
    float bx = wp_axis(b, ray->kx) - ray->sx * bz;
    float by = wp_axis(b, ray->ky) - ray->sy * bz;
    float cx = wp_axis(c, ray->kx) - ray->sx * cz;
    float cy = wp_axis(c, ray->ky) - ray->sy * cz;

    float u = cx * by - cy * bx; /* edge p1-p2 */
    float v = ax * cy - ay * cx; /* edge p2-p0 */
    float w = bx * ay - by * ax; /* edge p0-p1 */
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f))
        return 0;
    /* A ray within about 1e-7 rad of the triangle's plane sees it as a sliver
     * thinner than the rounding of the sheared corners, and the edge values'
     * signs become noise: they could accept a ray passing far beside the
     * triangle (docs/stability.md, case 10). The ray's point (0, 0) must at
     * least lie in the box of the three projected corners, widened by their
     * rounding. A point the exact edge tests would accept always does, so
     * this rejects only wrong decisions, and it keeps the test watertight:
     * a ray through a shared edge or vertex lies in both triangles' boxes. */
    float slack =
        WP_SLIVER_GUARD_RELATIVE *
        fmax(fmax(wp_max_abs_component(a), wp_max_abs_component(b)), wp_max_abs_component(c));
    if (fmin(fmin(ax, bx), cx) > slack || fmax(fmax(ax, bx), cx) < -slack ||
        fmin(fmin(ay, by), cy) > slack || fmax(fmax(ay, by), cy) < -slack)
        return 0;
    float det = u + v + w;
    if (det == 0.0f)
        return 0; /* the ray lies in the triangle's plane */

    /* Scaled distance: t = T / det, tested without dividing. */
    float T = u * (ray->sz * az) + v * (ray->sz * bz) + w * (ray->sz * cz);
    if (det > 0.0f ? (T <= 0.0f || T >= t_max * det) : (T >= 0.0f || T <= t_max * det))
        return 0;
    *t = T / det;
    return 1;
}

/* Unnormalised front-face normal of a triangle. */
static inline float3 wp_triangle_normal(const WpTriangle* tri) {
    return cross(tri->v1.xyz - tri->v0.xyz, tri->v2.xyz - tri->v0.xyz);
}

#endif /* WP_TRIANGLE_H */
