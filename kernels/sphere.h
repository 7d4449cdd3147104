/* The ray-sphere test, in float32. It solves the quadratic in the form that
 * avoids catastrophic cancellation: the discriminant from the ray's
 * perpendicular distance to the centre (or directly, whichever rounds less),
 * and the two roots as c/q and q/a (Press et al., pbrt-v4), with the ray's
 * offset from the centre kept exactly (exact_arithmetic.h). docs/stability.md
 * measures it against the textbook b^2 - 4ac form, which lives on in the
 * stability tests only (tests/stability/naive.hpp).
 */
#ifndef WP_SPHERE_H
#define WP_SPHERE_H

#include "exact_arithmetic.h"

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

#endif /* WP_SPHERE_H */
