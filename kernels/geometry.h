/* Ray/primitive intersection and ray spawning, in float32.
 *
 * Triangles use the watertight test of Woop, Benthin and Wald (JCGT 2013): the
 * ray is sheared so it runs along +z, and each edge function is computed from
 * the two vertices of that edge alone. Two triangles sharing an edge compute
 * exactly negated edge values (multiplication commutes and subtraction is
 * exactly antisymmetric, as long as the compiler does not contract a*b - c*d
 * into an FMA, hence FP_CONTRACT OFF), so a ray can never slip between them.
 *
 * Spheres solve the quadratic in the form that avoids catastrophic
 * cancellation: the discriminant from the ray's perpendicular distance to the
 * centre, and the two roots as c/q and q/a (Press et al., pbrt-v4).
 *
 * Naive variants, for the stability tests only (docs/stability.md): they
 * compile in when a test kernel defines the switch, never in the renderer.
 *   WP_NAIVE_INTERSECTION=1  Moller-Trumbore triangles and the textbook
 *                            quadratic (b^2 - 4ac) for spheres;
 *   WP_NAIVE_OFFSET=1        a fixed offset of WP_NAIVE_OFFSET_EPSILON
 *                            instead of the relative one.
 */
#ifndef WP_GEOMETRY_H
#define WP_GEOMETRY_H

#include "wp_shared.h"

#pragma OPENCL FP_CONTRACT OFF

/* Spawned rays start off their surface, along the normal on the side they
 * leave by, so that rounding cannot make them hit the surface they left.
 *
 * The offset is relative: WP_RAY_OFFSET_RELATIVE times the magnitude of the
 * coordinates involved, which is the hit point and the primitive's own
 * vertices (or centre plus radius): the intersection test subtracts the ray
 * origin from the vertices, so its rounding error scales with both. A fixed
 * epsilon would be too big for a millimetre scene and too small for a
 * kilometre one; a relative one keeps the renderer scale-invariant. 2e-6 is
 * about 17 float ulps of that magnitude, above the few ulps of error of a
 * reprojected hit point and small enough that contact shadows stay closed. */
#define WP_RAY_OFFSET_RELATIVE 2.0e-6f
/* Keeps the offset non-zero at the exact origin. */
#define WP_RAY_OFFSET_FLOOR 1.0e-30f

#ifndef WP_NAIVE_INTERSECTION
#define WP_NAIVE_INTERSECTION 0
#endif
#ifndef WP_NAIVE_OFFSET
#define WP_NAIVE_OFFSET 0
#endif
/* How far outside the box of a triangle's projected corners a ray may pass
 * and still hit it, relative to the corners' distance from the ray origin:
 * about 8 float ulps, above the rounding of the sheared coordinates. */
#define WP_SLIVER_GUARD_RELATIVE 1.0e-6f

/* The naive variant's fixed offset: a typical "shadow epsilon". */
#define WP_NAIVE_OFFSET_EPSILON 1.0e-4f

static inline float wp_max_abs_component(float3 p) {
    return fmax(fmax(fabs(p.x), fabs(p.y)), fabs(p.z));
}

/* How far to offset a point on a primitive whose coordinates reach `scale`
 * in magnitude (see wp_triangle_scale, wp_sphere_scale). */
static inline float wp_offset_distance(float3 p, float scale) {
#if WP_NAIVE_OFFSET
    (void)p;
    (void)scale;
    return WP_NAIVE_OFFSET_EPSILON;
#else
    return WP_RAY_OFFSET_RELATIVE * fmax(wp_max_abs_component(p), scale) + WP_RAY_OFFSET_FLOOR;
#endif
}

/* Moves p off its surface to the side of `side_normal` (unit length). */
static inline float3 wp_offset_ray_origin(float3 p, float3 side_normal, float scale) {
    return p + side_normal * wp_offset_distance(p, scale);
}

static inline float wp_triangle_scale(const WpTriangle* t) {
    return fmax(wp_max_abs_component(t->v0.xyz),
                fmax(wp_max_abs_component(t->v1.xyz), wp_max_abs_component(t->v2.xyz)));
}

static inline float wp_sphere_scale(float4 center_radius) {
    return wp_max_abs_component(center_radius.xyz) + center_radius.w;
}

static inline float wp_axis(float3 v, int axis) {
    return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

/* What the watertight test needs of a ray, computed once per ray. */
typedef struct {
    float3 origin;
    int kx, ky, kz; /* kz: the direction's dominant axis */
    float sx, sy, sz;
#if WP_NAIVE_INTERSECTION
    float3 direction;
#endif
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
#if WP_NAIVE_INTERSECTION
    r.direction = direction;
#endif
    return r;
}

/* Returns 1 and sets *t if the ray hits the triangle at 0 < t < t_max.
 * Both faces are hit; points on an edge or vertex count as inside. */
static inline int wp_intersect_triangle(const WpShearedRay* ray, float3 p0, float3 p1, float3 p2,
                                        float t_max, float* t) {
#if WP_NAIVE_INTERSECTION
    /* Moller-Trumbore (1997), both faces, rejecting only det == 0: each
     * triangle computes its barycentrics from its own edge vectors, so two
     * triangles sharing an edge round differently and a ray through the
     * edge can miss both. */
    {
        float3 e1 = p1 - p0, e2 = p2 - p0;
        float3 pv = cross(ray->direction, e2);
        float det = dot(e1, pv);
        if (det == 0.0f)
            return 0;
        float inv_det = 1.0f / det;
        float3 s = ray->origin - p0;
        float bu = dot(s, pv) * inv_det;
        if (bu < 0.0f || bu > 1.0f)
            return 0;
        float3 qv = cross(s, e1);
        float bv = dot(ray->direction, qv) * inv_det;
        if (bv < 0.0f || bu + bv > 1.0f)
            return 0;
        float naive_t = dot(e2, qv) * inv_det;
        if (!(naive_t > 0.0f && naive_t < t_max))
            return 0;
        *t = naive_t;
        return 1;
    }
#endif
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

/* Error-free transformations: a - b == s + *err exactly (Knuth's TwoSum,
 * valid for any rounding-to-nearest floats, hence FP_CONTRACT OFF), and
 * a * b == p + *err exactly (the FMA gives the product's rounding error). */
static inline float3 wp_two_diff3(float3 a, float3 b, float3* err) {
    float3 s = a - b;
    float3 bb = s - a;
    *err = (a - (s - bb)) - (b + bb);
    return s;
}

static inline float wp_two_sum(float a, float b, float* err) {
    float s = a + b;
    float bb = s - a;
    *err = (a - (s - bb)) + (b - bb);
    return s;
}

static inline float wp_two_product(float a, float b, float* err) {
    float p = a * b;
    *err = fma(a, b, -p);
    return p;
}

/* c = |f + f_error|^2 - r^2 to nearly full float precision, even when |f|^2
 * and r^2 agree in most of their digits (the ray starts close to a sphere
 * much bigger than the distance, as on a planet-sized ground). The squares
 * are split exactly into value + rounding error and summed with
 * compensation; the plain dot(f, f) - r * r would keep only the absolute
 * precision of |f|^2 (8 for a radius of 1e4, against c = 3.4e4 at 1.7 above
 * that ground: a 2e-4 error in t). */
static inline float wp_sphere_c(float3 f, float3 f_error, float radius) {
    float ex, ey, ez, er, s1, s2, s3;
    float px = wp_two_product(f.x, f.x, &ex);
    float py = wp_two_product(f.y, f.y, &ey);
    float pz = wp_two_product(f.z, f.z, &ez);
    float rr = wp_two_product(radius, radius, &er);
    float sum = wp_two_sum(px, py, &s1);
    sum = wp_two_sum(sum, pz, &s2);
    sum = wp_two_sum(sum, -rr, &s3);
    /* The small terms: compensations, product errors, 2 f.f_error + |f_error|^2. */
    float small = ((s1 + s2) + s3) + ((ex + ey) + (ez - er)) + dot(f + f + f_error, f_error);
    return sum + small;
}

/* Returns 1 and sets *t if the ray hits the sphere at 0 < t < t_max. */
static inline int wp_intersect_sphere(float3 origin, float3 direction, float4 center_radius,
                                      float t_max, float* t) {
#if WP_NAIVE_INTERSECTION
    {
        /* The textbook quadratic: b^2 - 4ac cancels catastrophically when the
         * sphere is small and far (b^2 and 4ac agree in every float digit),
         * and -b + sqrt(...) cancels for the near root. */
        float3 f = origin - center_radius.xyz;
        float a = dot(direction, direction);
        float b = 2.0f * dot(f, direction);
        float c = dot(f, f) - center_radius.w * center_radius.w;
        float discriminant = b * b - 4.0f * a * c;
        if (discriminant < 0.0f)
            return 0;
        float root = sqrt(discriminant);
        float t_near = (-b - root) / (2.0f * a);
        float t_far = (-b + root) / (2.0f * a);
        float naive_hit = (t_near > 0.0f) ? t_near : t_far;
        if (!(naive_hit > 0.0f && naive_hit < t_max))
            return 0;
        *t = naive_hit;
        return 1;
    }
#endif
    float radius = center_radius.w;
    /* f = origin - centre, kept exactly as f + f_error: for a ray starting
     * near a big sphere (a radius-1e4 ground seen from 1.7 above it), the
     * rounding of f alone would move the surface by 5e-4. */
    float3 f_error;
    float3 f = wp_two_diff3(origin, center_radius.xyz, &f_error);
    float a = dot(direction, direction);
    float half_b = dot(f, direction) + dot(f_error, direction);
    float c = wp_sphere_c(f, f_error, radius);
    /* The discriminant half_b^2 - a c, whichever way rounds less:
     *  - from the perpendicular offset l of the centre from the ray line,
     *    a (r - l)(r + l): l's error is a few ulps of |f|, so this one
     *    suits a small or far sphere, where half_b^2 and a c agree in every
     *    float digit and the direct form cancels completely;
     *  - directly, with the accurate c: its error is a few ulps of
     *    half_b^2 + a |c|, far less than the other's (about r |f|) when the
     *    ray starts near a big sphere, where c is small. */
    float discriminant;
    if (half_b * half_b + a * fabs(c) < 2.0f * a * radius * (fabs(f.x) + fabs(f.y) + fabs(f.z))) {
        discriminant = half_b * half_b - a * c;
    } else {
        float3 perpendicular = (f - (half_b / a) * direction) + f_error;
        float l = length(perpendicular);
        discriminant = a * (radius - l) * (radius + l);
    }
    if (discriminant < 0.0f)
        return 0;
    float q = -(half_b + copysign(sqrt(discriminant), half_b));
    float t_far = q / a;
    float t_near = (q != 0.0f) ? c / q : t_far;
    if (t_near > t_far) {
        float s = t_near;
        t_near = t_far;
        t_far = s;
    }
    float hit = (t_near > 0.0f) ? t_near : t_far;
    if (!(hit > 0.0f && hit < t_max))
        return 0;
    *t = hit;
    return 1;
}

/* Unnormalised front-face normal of a triangle. */
static inline float3 wp_triangle_normal(const WpTriangle* tri) {
    return cross(tri->v1.xyz - tri->v0.xyz, tri->v2.xyz - tri->v0.xyz);
}

#endif /* WP_GEOMETRY_H */
