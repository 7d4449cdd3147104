/* The rough plastic (Mitsuba 3's `roughplastic`): a diffuse base under a
 * rough dielectric coating of index eta = int_ior / ext_ior, the coating's
 * microfacets isotropic (alpha_u == alpha_v, the loader's `alpha`) with
 * Mitsuba's distributions and Smith masking (bsdf/microfacet.h). In the local
 * frame of the shading normal, v = -wo towards the viewer, l = wi, h =
 * normalize(v + l):
 *
 *   pi f = pi s F(v.h) D(h) G1(v,h) G1(l,h) / (4 v.z l.z)     the coating
 *        + rho' T(v.z) T(l.z) / eta^2                          the base
 *   rho' = rho / (1 - R_int)          (linear, Mitsuba's default)
 *   rho' = rho / (1 - rho R_int)      (nonlinear)
 *
 * s the specular_reflectance, rho the diffuse_reflectance. T(mu) is the rough
 * coating's transmittance from outside at incidence cosine mu, and R_int its
 * hemispherical reflectance from inside, both integrated over the
 * microfacets by the host exactly as Mitsuba integrates them
 * (src/scene/material.cpp): T as a table of WP_ROUGH_TRANSMITTANCE_RES
 * values at mu = i / (RES - 1) interpolated linearly
 * (WpMaterial.rough_transmittance), R_int as WpMaterial.fdr_int. Unlike the
 * smooth plastic the coating's reflection is glossy, not delta, so the
 * coating is lit by next-event estimation too, under multiple importance
 * sampling. Like wavepath's other reflecting materials it reflects on both
 * sides (Mitsuba's is one-sided; the export wraps it in `twosided`).
 *
 * sample() picks the coating with probability P = (1 - T(v.z)) w / ((1 -
 * T(v.z)) w + T(v.z) (1 - w)), w = WpMaterial.specular_weight (Mitsuba's
 * specular_sampling_weight), then a normal visible from v reflected about, or
 * a cosine-distributed direction for the base, from the lobe choice's number
 * rescaled (Mitsuba has a third number for the choice; both are unbiased with
 * the same density). The density is Mitsuba's mixture of the two:
 *
 *   pdf = P D_v(h) / (4 l.h) + (1 - P) l.z / pi,
 *
 * and the weight f cos / pdf of the whole BSDF, as Mitsuba weighs it. */
#ifndef WP_BSDF_ROUGHPLASTIC_H
#define WP_BSDF_ROUGHPLASTIC_H

#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/microfacet.h"
#include "sampling.h"

/* T(mu) from the table, as Mitsuba's lerp_gather reads it (mu in [0, 1]). */
static inline float wp_roughplastic_transmittance(const WpMaterial* m, float mu) {
    float x = clamp(mu, 0.0f, 1.0f) * (float)(WP_ROUGH_TRANSMITTANCE_RES - 1);
    int i = min((int)x, WP_ROUGH_TRANSMITTANCE_RES - 2);
    return mix(m->rough_transmittance[i], m->rough_transmittance[i + 1], x - (float)i);
}

/* The probability of sampling the coating at v.z = cos_i. */
static inline float wp_roughplastic_specular_probability(const WpMaterial* m, float cos_i) {
    float t_i = wp_roughplastic_transmittance(m, cos_i);
    float specular = (1.0f - t_i) * m->specular_weight;
    float diffuse = t_i * (1.0f - m->specular_weight);
    return specular + diffuse > 0.0f ? specular / (specular + diffuse) : 0.5f;
}

/* pi f and the density of l (the formulas above), in the local frame. */
static inline void wp_roughplastic_eval_local(const WpMaterial* m, float3 v, float3 l, float3* f_pi,
                                              float* pdf) {
    *f_pi = (float3)(0.0f);
    *pdf = 0.0f;
    if (!(v.z > 0.0f && l.z > 0.0f))
        return;
    float cos_i = fmin(v.z, 1.0f), cos_o = fmin(l.z, 1.0f);
    float3 h = normalize(v + l);
    WpMicrofacet d;
    wp_microfacet_of(m, &d);
    float cos_t;
    float fresnel = wp_fresnel_dielectric(clamp(dot(v, h), 0.0f, 1.0f), m->eta.x, &cos_t);
    float g = wp_microfacet_g1(&d, v, h) * wp_microfacet_g1(&d, l, h);
    float3 coating =
        m->specular.xyz * (WP_PI * fresnel * wp_microfacet_d(&d, h) * g / (4.0f * v.z * l.z));
    float3 rho = m->reflectance.xyz;
    float3 base = m->nonlinear ? rho / (1.0f - rho * m->fdr_int) : rho / (1.0f - m->fdr_int);
    float transmitted = wp_roughplastic_transmittance(m, cos_i) *
                        wp_roughplastic_transmittance(m, cos_o) / (m->eta.x * m->eta.x);
    *f_pi = coating + base * transmitted;
    float p_specular = wp_roughplastic_specular_probability(m, cos_i);
    float l_h = dot(l, h);
    float specular_pdf = l_h > 0.0f ? wp_microfacet_pdf_visible(&d, v, h) / (4.0f * l_h) : 0.0f;
    *pdf = p_specular * specular_pdf + (1.0f - p_specular) * cos_o * (1.0f / WP_PI);
    if (!isfinite(*pdf) || !all(isfinite(*f_pi))) {
        *f_pi = (float3)(0.0f);
        *pdf = 0.0f;
    }
}

static inline void wp_roughplastic_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* p,
                                          float u1, float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    float3 t, b, n = p->n;
    wp_make_basis(n, &t, &b);
    float3 v = (float3)(-dot(wo, t), -dot(wo, b), -dot(wo, n));
    if (!(v.z > 0.0f)) {
        wp_bsdf_no_sample(out);
        return;
    }
    float p_specular = wp_roughplastic_specular_probability(m, fmin(v.z, 1.0f));
    int specular = u1 < p_specular;
    float u = specular ? u1 / p_specular : (u1 - p_specular) / (1.0f - p_specular);
    u = fmin(u, 0x1.fffffep-1f);
    float3 l;
    if (specular) {
        WpMicrofacet d;
        wp_microfacet_of(m, &d);
        float3 h = wp_microfacet_sample_visible(&d, v, u, u2);
        l = 2.0f * dot(v, h) * h - v;
    } else {
        l = wp_sample_cosine_hemisphere((float3)(0.0f, 0.0f, 1.0f), u, u2);
    }
    WpBsdfSample s;
    float3 f_pi;
    wp_roughplastic_eval_local(m, v, l, &f_pi, &s.pdf);
    if (!(s.pdf > 0.0f)) { /* reflected below the surface: Mitsuba's weight is 0 there too */
        wp_bsdf_no_sample(out);
        return;
    }
    s.direction = normalize(l.x * t + l.y * b + l.z * n);
    s.weight = f_pi * (l.z / (WP_PI * s.pdf));
    s.flags = WP_BSDF_REFLECTION | (specular ? WP_BSDF_GLOSSY : WP_BSDF_DIFFUSE);
    s.eta = 1.0f;
    *out = s;
}

/* pi f and (into *pdf) the density of wi, from one evaluation
 * (wp_bsdf_eval_pi_pdf). */
static inline float3 wp_roughplastic_eval_pi_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                                 const WpShadingPoint* p, float* pdf) {
    float3 f_pi;
    wp_roughplastic_eval_local(m, -wp_to_local(wo, p->n), wp_to_local(wi, p->n), &f_pi, pdf);
    return f_pi;
}

static inline float3 wp_roughplastic_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                             const WpShadingPoint* p) {
    float pdf;
    return wp_roughplastic_eval_pi_pdf(m, wo, wi, p, &pdf);
}

static inline float wp_roughplastic_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                        const WpShadingPoint* p) {
    float pdf;
    wp_roughplastic_eval_pi_pdf(m, wo, wi, p, &pdf);
    return pdf;
}

static inline int wp_roughplastic_is_delta(void) {
    return 0;
}

static inline int wp_roughplastic_transmits(void) {
    return 0;
}

#endif /* WP_BSDF_ROUGHPLASTIC_H */
