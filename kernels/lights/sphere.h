/* An emitting sphere (Mitsuba 3's `area` emitter on a `sphere`): its
 * material's emission leaves the outside of the sphere, the side its normal
 * points to (one-sided, as Mitsuba's area lights are).
 *
 * Next-event estimation samples it by the cone of directions it subtends
 * from the shading point, not by its area: uniform in that cone's solid
 * angle, so a small or distant sphere costs no more noise than a near one
 * (sampled by area, most points of a small distant sphere face away or hide
 * behind its front, and the density of the rest swings with the distance).
 * Every direction in the cone meets the sphere's near side, which faces the
 * point, so the estimate is exact up to visibility: L times the cone's
 * solid angle times the mean cosine. From inside the sphere (or on it)
 * nothing is sampled: the inside does not emit.
 */
#ifndef WP_LIGHTS_SPHERE_H
#define WP_LIGHTS_SPHERE_H

#include "sampling.h"
#include "sphere.h"
#include "wp_shared.h"

/* The cone the sphere (centre xyz, radius w) subtends from p: 1 - cos of its
 * half-angle in *one_minus_cos, the distance to the centre in *distance,
 * and whether p is outside the sphere (else there is no cone). 1 - cos is
 * computed as sin^2 / (1 + cos), not as the difference, which rounds to 0 for
 * a sphere smaller than a 1/2000th of its distance. */
static inline int wp_sphere_cone(float3 p, float4 center_radius, float* one_minus_cos,
                                 float* distance) {
    float3 to_center = center_radius.xyz - p;
    float d2 = dot(to_center, to_center);
    float r = center_radius.w;
    float sin2 = r * r / d2;
    if (!(sin2 < 1.0f))
        return 0;
    *one_minus_cos = sin2 / (1.0f + sqrt(1.0f - sin2));
    *distance = sqrt(d2);
    return 1;
}

/* The solid-angle density of the cone sample from p (0 from inside). */
static inline float wp_sphere_light_pdf(float3 p, float4 center_radius) {
    float one_minus_cos, distance;
    if (!wp_sphere_cone(p, center_radius, &one_minus_cos, &distance))
        return 0.0f;
    return 1.0f / (2.0f * WP_PI * one_minus_cos);
}

/* A direction *wi uniformly in the cone from p, the distance *t along it to
 * the sphere's near side, and its density *pdf. Returns 0 from inside. */
static inline int wp_sample_sphere_light(float3 p, float4 center_radius, float u, float v,
                                         float3* wi, float* t, float* pdf) {
    float one_minus_cos, distance;
    if (!wp_sphere_cone(p, center_radius, &one_minus_cos, &distance))
        return 0;
    float3 axis = (center_radius.xyz - p) * (1.0f / distance);
    /* cos theta uniform in [cos theta_max, 1]: 1 - cos theta = u (1 - cos theta_max). */
    float s = u * one_minus_cos;
    float cos_theta = 1.0f - s;
    float sin_theta = sqrt(fmax(0.0f, s * (2.0f - s)));
    float phi = 2.0f * WP_PI * v;
    float3 tangent, bitangent;
    wp_make_basis(axis, &tangent, &bitangent);
    *wi = normalize(axis * cos_theta + (tangent * cos(phi) + bitangent * sin(phi)) * sin_theta);
    /* The near intersection of the ray p + t wi with the sphere; the
     * discriminant, r^2 - (d sin theta)^2, is >= 0 inside the cone up to
     * rounding at its rim. */
    float r = center_radius.w;
    float along = distance * cos_theta, off = distance * sin_theta;
    *t = along - sqrt(fmax(0.0f, (r - off) * (r + off)));
    *pdf = 1.0f / (2.0f * WP_PI * one_minus_cos);
    return *t > 0.0f;
}

#endif /* WP_LIGHTS_SPHERE_H */
