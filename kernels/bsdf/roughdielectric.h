/* The rough dielectric (Mitsuba 3's `roughdielectric`): frosted glass, a
 * dielectric interface made of microfacets (Walter et al., "Microfacet Models
 * for Refraction through Rough Surfaces", EGSR 2007), with Mitsuba's
 * distributions, roughness and separable Smith masking (bsdf/microfacet.h).
 * In the local frame of the shading normal on the ray's side (bsdf/frame.h:
 * alpha_u along the surface's tangent dp/du), v = -wo the
 * direction towards the viewer (v.z > 0), eta the index beyond relative to
 * the ray's side (as for `dielectric`), h the microfacet normal:
 *
 *   reflection,   l.z > 0:  f = F(v.h) D(h) G1(v,h) G1(l,h) / (4 v.z |l.z|),
 *                           h = normalize(v + l);
 *   transmission, l.z < 0:  f = (1 - F(v.h)) D(h) G1(v,h) G1(l,h) |v.h| |l.h| /
 *                               (v.z |l.z| (v.h + eta l.h)^2),
 *                           h = -normalize(v + eta l), turned to v's side,
 *
 * the transmitted part without Walter's eta^2 because paths carry radiance
 * (the (n_from / n_to)^2 of bsdf/dielectric.h; Mitsuba's radiance mode does
 * the same).
 *
 * Sampling, as Mitsuba 3 does it: a normal h visible from v (Heitz) from two
 * numbers, then the side from a third (WP_DIM_BSDF_LOBE): reflection with
 * probability F(v.h), the microfacet's own Fresnel reflectance, and l
 * reflected or refracted about h. The weight is then G1(l,h), times
 * (n_from / n_to)^2 for transmission: at most 1 before that factor, whatever
 * the angle. (Picking the side first, by the smooth interface's F(v.z) within
 * [0.05, 0.95], as wavepath did with two numbers, weighs a sample by
 * F(v.h) / P or (1 - F(v.h)) / (1 - P): up to 20, and 43 with the factor, for
 * a ray inside the glass past the critical angle that a tilted microfacet
 * lets out. Those rare bright samples were the frosted sphere's speckle on
 * the showcase, docs/performance.md.)
 *
 * Next-event estimation sees lights on both sides of a surface that
 * transmits (kernels/lights.h), and weighs them against BSDF sampling by
 * multiple importance sampling, as for the rough conductor. */
#ifndef WP_BSDF_ROUGHDIELECTRIC_H
#define WP_BSDF_ROUGHDIELECTRIC_H

#include "bsdf/dielectric.h"
#include "bsdf/frame.h"
#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/microfacet.h"
#include "color.h"

/* The microfacet normal that takes v to l (on v's side; 0 when none does). */
static inline float3 wp_roughdielectric_half(float3 v, float3 l, float eta) {
    float3 h = l.z > 0.0f ? v + l : -(v + eta * l);
    float len = length(h);
    if (!(len > 0.0f))
        return (float3)(0.0f);
    h /= len;
    return h.z < 0.0f ? -h : h;
}

/* pi f and the density of l (the formulas above), in the local frame. */
static inline void wp_roughdielectric_eval_local(const WpMaterial* m, float3 v, float3 l, float eta,
                                                 float3* f_pi, float* pdf) {
    *f_pi = (float3)(0.0f);
    *pdf = 0.0f;
    if (!(v.z > 0.0f) || l.z == 0.0f)
        return;
    int reflect = l.z > 0.0f;
    float3 h = wp_roughdielectric_half(v, l, eta);
    float v_h = dot(v, h), l_h = dot(l, h);
    /* Both directions on their own side of the microfacet. */
    if (!(v_h > 0.0f) || !(reflect ? l_h > 0.0f : l_h < 0.0f))
        return;
    WpMicrofacet d;
    wp_microfacet_of(m, &d);
    float cos_t;
    float fresnel = wp_fresnel_dielectric(fmin(1.0f, v_h), eta, &cos_t);
    float g = wp_microfacet_g1(&d, v, h) * wp_microfacet_g1(&d, l, h);
    float dh = wp_microfacet_d(&d, h);
    float visible = wp_microfacet_pdf_visible(&d, v, h);
    if (reflect) {
        *f_pi = m->reflectance.xyz * (WP_PI * fresnel * dh * g / (4.0f * v.z * l.z));
        *pdf = fresnel * visible / (4.0f * v_h);
    } else {
        float denominator = v_h + eta * l_h;
        float jacobian = eta * eta * fabs(l_h) / (denominator * denominator);
        /* Radiance: Walter's eta^2 cancels against (1 / eta)^2. */
        *f_pi = m->transmittance.xyz * (WP_PI * (1.0f - fresnel) * dh * g * v_h * fabs(l_h) /
                                        (v.z * fabs(l.z) * denominator * denominator));
        *pdf = (1.0f - fresnel) * visible * jacobian;
    }
    if (!isfinite(*pdf) || !all(isfinite(*f_pi))) {
        *f_pi = (float3)(0.0f);
        *pdf = 0.0f;
    }
}

static inline void wp_roughdielectric_sample(const WpMaterial* m, float3 wo,
                                             const WpShadingPoint* p, float u1, float u2,
                                             float u_lobe, WpBsdfSample* out) {
    float3 t, b, n = p->n;
    wp_bsdf_frame(m, p, &t, &b);
    float3 v = (float3)(-dot(wo, t), -dot(wo, b), -dot(wo, n));
    float eta = wp_dielectric_eta(m, p);
    if (!(v.z > 0.0f)) {
        wp_bsdf_no_sample(out);
        return;
    }
    WpMicrofacet d;
    wp_microfacet_of(m, &d);
    float3 h = wp_microfacet_sample_visible(&d, v, u1, u2);
    float v_h = dot(v, h);
    float cos_t;
    /* 1 under total internal reflection at this microfacet: it only reflects. */
    float fresnel = wp_fresnel_dielectric(fmin(1.0f, fmax(0.0f, v_h)), eta, &cos_t);
    int reflect = u_lobe < fresnel;
    float inv_eta = 1.0f / eta;
    float3 l = reflect ? 2.0f * v_h * h - v : (inv_eta * v_h - cos_t) * h - inv_eta * v;
    float l_h = dot(l, h);
    if (!(v_h > 0.0f) || !(reflect ? l.z > 0.0f : l.z < 0.0f)) {
        wp_bsdf_no_sample(out);
        return;
    }
    /* The density of l: h's, times the side's probability, times the
     * Jacobian of the map from h to l (eval_local's). */
    float visible = wp_microfacet_pdf_visible(&d, v, h);
    float pdf;
    if (reflect) {
        pdf = fresnel * visible / (4.0f * v_h);
    } else {
        float denominator = v_h + eta * l_h;
        pdf = (1.0f - fresnel) * visible * eta * eta * fabs(l_h) / (denominator * denominator);
    }
    /* f cos / pdf: everything but l's masking cancels. */
    float3 weight = (reflect ? m->reflectance.xyz : m->transmittance.xyz * (inv_eta * inv_eta)) *
                    wp_microfacet_g1(&d, l, h);
    if (!(pdf > 0.0f) || !isfinite(pdf) || wp_is_black(weight)) {
        wp_bsdf_no_sample(out);
        return;
    }
    WpBsdfSample s;
    s.pdf = pdf;
    s.direction = normalize(l.x * t + l.y * b + l.z * n);
    s.weight = weight;
    s.flags = (reflect ? WP_BSDF_REFLECTION : WP_BSDF_TRANSMISSION) | WP_BSDF_GLOSSY;
    s.eta = reflect ? 1.0f : eta;
    *out = s;
}

/* pi f and (into *pdf) the density of wi, from one evaluation
 * (wp_bsdf_eval_pi_pdf). */
static inline float3 wp_roughdielectric_eval_pi_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                                    const WpShadingPoint* p, float* pdf) {
    float3 f_pi;
    wp_roughdielectric_eval_local(m, -wp_bsdf_to_local(m, p, wo), wp_bsdf_to_local(m, p, wi),
                                  wp_dielectric_eta(m, p), &f_pi, pdf);
    return f_pi;
}

static inline float3 wp_roughdielectric_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                                const WpShadingPoint* p) {
    float pdf;
    return wp_roughdielectric_eval_pi_pdf(m, wo, wi, p, &pdf);
}

static inline float wp_roughdielectric_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                           const WpShadingPoint* p) {
    float pdf;
    wp_roughdielectric_eval_pi_pdf(m, wo, wi, p, &pdf);
    return pdf;
}

static inline int wp_roughdielectric_is_delta(void) {
    return 0;
}

static inline int wp_roughdielectric_transmits(void) {
    return 1;
}

#endif /* WP_BSDF_ROUGHDIELECTRIC_H */
