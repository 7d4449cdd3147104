/* The thin dielectric (Mitsuba 3's `thindielectric`): a pane of glass of no
 * thickness, a window or a soap film. Light reflects off it with the Fresnel
 * reflectance of the two interfaces summed over every internal bounce,
 * R' = R + T^2 R / (1 - R^2) = 2 R / (1 + R), and passes straight through
 * with 1 - R' (the two refractions cancel: no bending, no solid-angle
 * factor). Both lobes are delta, picked with those probabilities. eta
 * (WpMaterial.eta.x) is int_ior / ext_ior; the pane is the same from both
 * sides. */
#ifndef WP_BSDF_THINDIELECTRIC_H
#define WP_BSDF_THINDIELECTRIC_H

#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/mirror.h"

static inline void wp_thindielectric_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* p,
                                            float u1, float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    (void)u2;
    float3 n = p->n;
    float cos_t;
    float r = wp_fresnel_dielectric(fmin(1.0f, fmax(0.0f, -dot(wo, n))), m->eta.x, &cos_t);
    r *= 2.0f / (1.0f + r);
    WpBsdfSample s;
    s.pdf = 0.0f;
    s.eta = 1.0f;
    if (u1 < r) {
        s.direction = wp_reflect(wo, n);
        s.weight = m->reflectance.xyz;
        s.flags = WP_BSDF_REFLECTION | WP_BSDF_DELTA;
    } else {
        s.direction = wo;
        s.weight = m->transmittance.xyz;
        s.flags = WP_BSDF_TRANSMISSION | WP_BSDF_DELTA;
    }
    *out = s;
}

static inline float3 wp_thindielectric_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                               const WpShadingPoint* p) {
    (void)m, (void)wo, (void)wi, (void)p;
    return (float3)(0.0f);
}

static inline float wp_thindielectric_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                          const WpShadingPoint* p) {
    (void)m, (void)wo, (void)wi, (void)p;
    return 0.0f;
}

static inline int wp_thindielectric_is_delta(void) {
    return 1;
}

static inline int wp_thindielectric_transmits(void) {
    return 1;
}

#endif /* WP_BSDF_THINDIELECTRIC_H */
