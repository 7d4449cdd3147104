/* The perfect mirror: a delta BSDF that reflects about the normal and keeps
 * the reflectance of the throughput. No other direction meets it, so eval
 * and pdf are 0 and next-event estimation skips mirrors. */
#ifndef WP_BSDF_MIRROR_H
#define WP_BSDF_MIRROR_H

#include "bsdf/interface.h"

/* Perfect mirror reflection of d about the unit normal n. */
static inline float3 wp_reflect(float3 d, float3 n) {
    return d - 2.0f * dot(d, n) * n;
}

static inline void wp_mirror_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* point,
                                    float u1, float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    float3 n = point->n;
    (void)u1;
    (void)u2;
    WpBsdfSample s;
    s.direction = wp_reflect(wo, n);
    s.weight = m->reflectance.xyz;
    s.pdf = 0.0f;
    s.flags = WP_BSDF_REFLECTION | WP_BSDF_DELTA;
    s.eta = 1.0f;
    *out = s;
}

static inline float3 wp_mirror_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                       const WpShadingPoint* point) {
    (void)point;
    (void)m;
    (void)wo;
    (void)wi;
    return (float3)(0.0f);
}

static inline float wp_mirror_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                  const WpShadingPoint* point) {
    (void)point;
    (void)m;
    (void)wo;
    (void)wi;
    return 0.0f;
}

/* A delta BSDF: next-event estimation cannot reach it. */
static inline int wp_mirror_is_delta(void) {
    return 1;
}

static inline int wp_mirror_transmits(void) {
    return 0;
}

#endif /* WP_BSDF_MIRROR_H */
