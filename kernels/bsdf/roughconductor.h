/* The rough conductor (Mitsuba 3's `roughconductor`): a microfacet BRDF
 * (Cook-Torrance; Walter et al., "Microfacet Models for Refraction through
 * Rough Surfaces", EGSR 2007) with the conductor's complex Fresnel term,
 *     f(v, l) = F(dot(v, h)) D(h) G1(v, h) G1(l, h) / (4 cos_v cos_l),
 * h = normalize(v + l), v = -wo the direction towards the viewer. Sampled by
 * the normals visible from v (bsdf/microfacet.h), so the weight f cos / pdf is
 * F G1(l, h) and the density of l is D_v(h) / (4 dot(v, h)).
 *
 * The local frame is bsdf/frame.h's: alpha_u runs along the surface's
 * tangent dp/du, as in Mitsuba. Reflection only: a direction below the
 * shading hemisphere, seen or sampled, carries nothing. */
#ifndef WP_BSDF_ROUGHCONDUCTOR_H
#define WP_BSDF_ROUGHCONDUCTOR_H

#include "bsdf/frame.h"
#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/microfacet.h"

static inline void wp_roughconductor_sample(const WpMaterial* m, float3 wo,
                                            const WpShadingPoint* point, float u1, float u2,
                                            float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    float3 n = point->n;
    float3 t, b;
    wp_bsdf_frame(m, point, &t, &b);
    float3 v = (float3)(-dot(wo, t), -dot(wo, b), -dot(wo, n));
    if (!(v.z > 0.0f)) {
        wp_bsdf_no_sample(out);
        return;
    }
    WpMicrofacet d;
    wp_microfacet_of(m, &d);
    float3 h = wp_microfacet_sample_visible(&d, v, u1, u2);
    float v_dot_h = dot(v, h);
    float3 l = 2.0f * v_dot_h * h - v;
    float pdf_h = wp_microfacet_pdf_visible(&d, v, h);
    if (!(l.z > 0.0f && v_dot_h > 0.0f && pdf_h > 0.0f)) {
        wp_bsdf_no_sample(out);
        return;
    }
    WpBsdfSample s;
    s.direction = normalize(l.x * t + l.y * b + l.z * n);
    s.weight = wp_conductor_reflectance(m, fmin(1.0f, v_dot_h)) * wp_microfacet_g1(&d, l, h);
    s.pdf = pdf_h / (4.0f * v_dot_h);
    s.flags = WP_BSDF_REFLECTION | WP_BSDF_GLOSSY;
    s.eta = 1.0f;
    *out = s;
}

static inline float3 wp_roughconductor_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                               const WpShadingPoint* point) {
    float3 v = -wp_bsdf_to_local(m, point, wo), l = wp_bsdf_to_local(m, point, wi);
    if (!(v.z > 0.0f && l.z > 0.0f))
        return (float3)(0.0f);
    float3 h = normalize(v + l);
    WpMicrofacet d;
    wp_microfacet_of(m, &d);
    float g = wp_microfacet_g1(&d, v, h) * wp_microfacet_g1(&d, l, h);
    float v_dot_h = fmin(1.0f, fmax(0.0f, dot(v, h)));
    return wp_conductor_reflectance(m, v_dot_h) *
           (WP_PI * wp_microfacet_d(&d, h) * g / (4.0f * v.z * l.z));
}

static inline float wp_roughconductor_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                          const WpShadingPoint* point) {
    float3 v = -wp_bsdf_to_local(m, point, wo), l = wp_bsdf_to_local(m, point, wi);
    if (!(v.z > 0.0f && l.z > 0.0f))
        return 0.0f;
    float3 h = normalize(v + l);
    float v_dot_h = dot(v, h);
    if (!(v_dot_h > 0.0f))
        return 0.0f;
    WpMicrofacet d;
    wp_microfacet_of(m, &d);
    return wp_microfacet_pdf_visible(&d, v, h) / (4.0f * v_dot_h);
}

static inline int wp_roughconductor_is_delta(void) {
    return 0;
}

static inline int wp_roughconductor_transmits(void) {
    return 0;
}

#endif /* WP_BSDF_ROUGHCONDUCTOR_H */
