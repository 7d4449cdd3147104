/* The smooth dielectric (Mitsuba 3's `dielectric`): an interface between two
 * indices of refraction, glass or water, that reflects with the Fresnel
 * reflectance R and refracts with 1 - R. Both lobes are delta: sample() picks
 * reflection with probability R (so the weight is specular_reflectance or
 * specular_transmittance, with no Fresnel factor left), eval and pdf are 0,
 * and next-event estimation skips it (no caustics through it by light
 * sampling, as in Mitsuba's path tracer).
 *
 * eta (WpMaterial.eta.x) is int_ior / ext_ior: the front side of the
 * primitive (the outside of a sphere, the side a triangle's winding faces) is
 * the exterior. A ray arriving from the front sees eta, from the back 1 / eta.
 *
 * Paths are traced from the camera, so they carry radiance: light crossing
 * into a denser medium is compressed into a smaller solid angle, and the
 * refracted weight takes (n_from / n_to)^2, Mitsuba's TransportMode::Radiance
 * factor (Veach's thesis, 5.2). Under total internal reflection R = 1. */
#ifndef WP_BSDF_DIELECTRIC_H
#define WP_BSDF_DIELECTRIC_H

#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/mirror.h"

/* The index of refraction on the far side relative to the ray's side. */
static inline float wp_dielectric_eta(const WpMaterial* m, const WpShadingPoint* p) {
    return p->front_face ? m->eta.x : 1.0f / m->eta.x;
}

static inline void wp_dielectric_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* p,
                                        float u1, float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    (void)u2;
    float3 n = p->n;
    float cos_i = fmin(1.0f, fmax(0.0f, -dot(wo, n)));
    float eta = wp_dielectric_eta(m, p);
    float cos_t;
    float r = wp_fresnel_dielectric(cos_i, eta, &cos_t);
    WpBsdfSample s;
    s.pdf = 0.0f;
    if (u1 < r) {
        s.direction = wp_reflect(wo, n);
        s.weight = m->reflectance.xyz;
        s.flags = WP_BSDF_REFLECTION | WP_BSDF_DELTA;
        s.eta = 1.0f;
    } else {
        /* Snell: the tangential part shrinks by 1 / eta, the normal part is
         * cos_t on the far side. */
        float inv_eta = 1.0f / eta;
        s.direction = normalize(inv_eta * wo + (inv_eta * cos_i - cos_t) * n);
        s.weight = m->transmittance.xyz * (inv_eta * inv_eta);
        s.flags = WP_BSDF_TRANSMISSION | WP_BSDF_DELTA;
        s.eta = eta;
    }
    *out = s;
}

static inline float3 wp_dielectric_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                           const WpShadingPoint* p) {
    (void)m, (void)wo, (void)wi, (void)p;
    return (float3)(0.0f);
}

static inline float wp_dielectric_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                      const WpShadingPoint* p) {
    (void)m, (void)wo, (void)wi, (void)p;
    return 0.0f;
}

static inline int wp_dielectric_is_delta(void) {
    return 1;
}

static inline int wp_dielectric_transmits(void) {
    return 1;
}

#endif /* WP_BSDF_DIELECTRIC_H */
