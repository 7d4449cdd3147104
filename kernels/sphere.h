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

/* Written on scalars, not float3, like the triangle test (triangle.h), so
 * that the traversal loop vectorises across work-items; each line is the
 * float3 expression it replaces, component by component, in the same order
 * (dot(a, b) is a.x b.x + a.y b.y + a.z b.z on PoCL). Where one axis, or one
 * of two alike steps, is written in another form that rounds exactly the
 * same (wp_two_diff_fma, the wp_two_sum forms, max(y, -y) for |y|), it is so that
 * LLVM's SLP vectoriser finds no alike lines to pack into short vectors,
 * which would keep PoCL from vectorising across work-items (traverse.h). */

/* |(x, y, z)| exactly as OpenCL's length() computes it on PoCL: the sum of
 * squares, rescaled by a power of two first when it would underflow or
 * overflow. Branch-free: with no rescaling the scale is 1, which changes
 * nothing. */
static inline float wp_length_xyz(float x, float y, float z) {
    float l2 = x * x + y * y + z * z;
    float scale = l2 < FLT_MIN ? 0x1.0p+86f : (l2 == INFINITY ? 0x1.0p-65f : 1.0f);
    float unscale = l2 < FLT_MIN ? 0x1.0p-86f : (l2 == INFINITY ? 0x1.0p+65f : 1.0f);
    float sx = x * scale, sy = y * scale, sz = z * scale;
    return sqrt(sx * sx + sy * sy + sz * sz) * unscale;
}

/* c = |f + f_error|^2 - r^2 to nearly full float precision, even when |f|^2
 * and r^2 agree in most of their digits (the ray starts close to a sphere
 * much bigger than the distance, as on a planet-sized ground). The squares
 * are split exactly into value + rounding error and summed with
 * compensation; the plain dot(f, f) - r * r would keep only the absolute
 * precision of |f|^2 (8 for a radius of 1e4, against c = 3.4e4 at 1.7 above
 * that ground: a 2e-4 error in t). */
static inline float wp_sphere_c(float fx, float fy, float fz, float ex, float ey, float ez,
                                float radius) {
    float qx, qy, qz, qr, s1, s2, s3;
    float px = wp_two_product(fx, fx, &qx);
    float py = wp_two_product(fy, fy, &qy);
    float pz = wp_two_product(fz, fz, &qz);
    float rr = wp_two_product(radius, radius, &qr);
    float sum = wp_two_sum(px, py, &s1);
    sum = wp_two_sum_fma(sum, pz, &s2); /* each in its own form, for SLP */
    sum = wp_two_sum_fma_first(sum, -rr, &s3);
    /* The small terms: compensations, product errors, 2 f.f_error + |f_error|^2. */
    float cross = ((fx + fx) + ex) * ex + ((fy + fy) + ey) * ey + ((fz + fz) + ez) * ez;
    float small = ((s1 + s2) + s3) + ((qx + qy) + (qz - qr)) + cross;
    return sum + small;
}

/* Returns 1 if the ray (origin o, direction d) hits the sphere (centre k,
 * radius) at 0 < t < t_max, and sets *t to the hit's t either way
 * (meaningless on a miss), so that a loop can select rather than branch. */
static inline int wp_sphere_test(float ox, float oy, float oz, float dx, float dy, float dz,
                                 float kx, float ky, float kz, float radius, float t_max,
                                 float* t) {
    /* f = origin - centre, kept exactly as f + f_error: for a ray starting
     * near a big sphere (a radius-1e4 ground seen from 1.7 above it), the
     * rounding of f alone would move the surface by 5e-4. */
    float ex, ey, ez;
    float fx = wp_two_diff(ox, kx, &ex);
    float fy = wp_two_diff_fma(oy, ky, &ey); /* another form, for SLP */
    float fz = wp_two_diff(oz, kz, &ez);
    float a = dx * dx + dy * dy + dz * dz;
    float half_b = (fx * dx + fy * dy + fz * dz) + (ex * dx + ey * dy + ez * dz);
    float c = wp_sphere_c(fx, fy, fz, ex, ey, ez, radius);
    /* The discriminant half_b^2 - a c, whichever way rounds less (both are
     * computed and one selected, which keeps the loop branch-free):
     *  - from the perpendicular offset l of the centre from the ray line,
     *    a (r - l)(r + l): l's error is a few ulps of |f|, so this one
     *    suits a small or far sphere, where half_b^2 and a c agree in every
     *    float digit and the direct form cancels completely;
     *  - directly, with the accurate c: its error is a few ulps of
     *    half_b^2 + a |c|, far less than the other's (about r |f|) when the
     *    ray starts near a big sphere, where c is small. */
    float along = half_b / a;
    float l = wp_length_xyz((fx - along * dx) + ex, (fy - along * dy) + ey, (fz - along * dz) + ez);
    float from_offset = a * (radius - l) * (radius + l);
    float direct = half_b * half_b - a * c;
    int use_direct =
        half_b * half_b + a * fabs(c) < 2.0f * a * radius * (fabs(fx) + fmax(fy, -fy) + fabs(fz));
    float discriminant = use_direct ? direct : from_offset;
    float q = -(half_b + copysign(sqrt(discriminant), half_b));
    float t_far = q / a;
    float t_near = (q != 0.0f) ? c / q : t_far;
    float first = t_near > t_far ? t_far : t_near;
    float second = t_near > t_far ? t_near : t_far;
    float hit = (first > 0.0f) ? first : second;
    *t = hit;
    return !(discriminant < 0.0f) && (hit > 0.0f && hit < t_max);
}

/* Returns 1 and sets *t if the ray hits the sphere at 0 < t < t_max. */
static inline int wp_intersect_sphere(float3 origin, float3 direction, float4 center_radius,
                                      float t_max, float* t) {
    float t_test;
    int hit = wp_sphere_test(origin.x, origin.y, origin.z, direction.x, direction.y, direction.z,
                             center_radius.x, center_radius.y, center_radius.z, center_radius.w,
                             t_max, &t_test);
    if (hit)
        *t = t_test;
    return hit;
}

#endif /* WP_SPHERE_H */
