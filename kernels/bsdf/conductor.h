/* The smooth conductor (Mitsuba 3's `conductor`): a delta BSDF that reflects
 * about the normal with the Fresnel reflectance of its complex index of
 * refraction eta + i k (per channel), times specular_reflectance. Like the
 * mirror, no other direction meets it: eval and pdf are 0 and next-event
 * estimation skips it. The mirror next-event estimation of
 * kernels/mirror_light.h is for the `mirror` kind only (Mitsuba's conductor
 * with material "none" loads as that kind, src/scene/load.cpp). */
#ifndef WP_BSDF_CONDUCTOR_H
#define WP_BSDF_CONDUCTOR_H

#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/mirror.h"

static inline void wp_conductor_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* point,
                                       float u1, float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    float3 n = point->n;
    (void)u1;
    (void)u2;
    WpBsdfSample s;
    s.direction = wp_reflect(wo, n);
    s.weight = wp_conductor_reflectance(m, fmin(1.0f, fmax(0.0f, -dot(wo, n))));
    s.pdf = 0.0f;
    s.flags = WP_BSDF_REFLECTION | WP_BSDF_DELTA;
    s.eta = 1.0f;
    *out = s;
}

static inline float3 wp_conductor_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                          const WpShadingPoint* point) {
    (void)m, (void)wo, (void)wi, (void)point;
    return (float3)(0.0f);
}

static inline float wp_conductor_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                     const WpShadingPoint* point) {
    (void)m, (void)wo, (void)wi, (void)point;
    return 0.0f;
}

static inline int wp_conductor_is_delta(void) {
    return 1;
}

static inline int wp_conductor_transmits(void) {
    return 0;
}

#endif /* WP_BSDF_CONDUCTOR_H */
