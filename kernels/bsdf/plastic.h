/* The smooth plastic (Mitsuba 3's `plastic`): a diffuse base under a smooth
 * dielectric coating of index eta = int_ior / ext_ior. Light either reflects
 * off the coating (a delta lobe, Fresnel reflectance F(cos_i) times
 * specular_reflectance), or enters it, scatters in the base and leaves:
 *
 *   pi f = rho' (1 - F(cos_i)) (1 - F(cos_o)) / eta^2,
 *   rho' = rho / (1 - F_dr)            (linear, Mitsuba's default)
 *   rho' = rho / (1 - rho F_dr)        (nonlinear: what the coating reflects
 *                                       back bounces in the base again, so
 *                                       colours saturate)
 *
 * F_dr the coating's diffuse Fresnel reflectance seen from inside
 * (WpMaterial.fdr_int, computed on the host as Mitsuba does). Like wavepath's
 * diffuse surfaces it reflects on both sides (Mitsuba's is one-sided; the
 * export wraps it in `twosided`).
 *
 * sample() picks the coating with probability P proportional to F(cos_i) w
 * against (1 - F(cos_i)) (1 - w), w = WpMaterial.specular_weight (Mitsuba's
 * specular_sampling_weight, mean specular over mean specular plus mean
 * diffuse reflectance), and the base by cosine sampling otherwise, reusing the
 * lobe choice's number. eval and pdf are the base's (the coating is delta):
 * next-event estimation lights the base, and emission found through the
 * coating counts as after a mirror. */
#ifndef WP_BSDF_PLASTIC_H
#define WP_BSDF_PLASTIC_H

#include "bsdf/fresnel.h"
#include "bsdf/interface.h"
#include "bsdf/mirror.h"
#include "sampling.h"

/* The probability of sampling the coating's reflection, at reflectance f_i. */
static inline float wp_plastic_specular_probability(const WpMaterial* m, float f_i) {
    float specular = f_i * m->specular_weight;
    float diffuse = (1.0f - f_i) * (1.0f - m->specular_weight);
    return specular + diffuse > 0.0f ? specular / (specular + diffuse) : 0.5f;
}

/* pi f of the base seen through the coating (the formula above). */
static inline float3 wp_plastic_base_pi(const WpMaterial* m, float f_i, float cos_o) {
    float cos_t;
    float f_o = wp_fresnel_dielectric(cos_o, m->eta.x, &cos_t);
    float3 rho = m->reflectance.xyz;
    float3 base = m->nonlinear ? rho / (1.0f - rho * m->fdr_int) : rho / (1.0f - m->fdr_int);
    return base * ((1.0f - f_i) * (1.0f - f_o) / (m->eta.x * m->eta.x));
}

static inline void wp_plastic_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* p,
                                     float u1, float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    float3 n = p->n;
    float cos_i = fmin(1.0f, -dot(wo, n));
    if (!(cos_i > 0.0f)) {
        wp_bsdf_no_sample(out);
        return;
    }
    float cos_t;
    float f_i = wp_fresnel_dielectric(cos_i, m->eta.x, &cos_t);
    float p_specular = wp_plastic_specular_probability(m, f_i);
    WpBsdfSample s;
    s.eta = 1.0f;
    if (u1 < p_specular) {
        s.direction = wp_reflect(wo, n);
        s.weight = m->specular.xyz * (f_i / p_specular);
        s.pdf = 0.0f;
        s.flags = WP_BSDF_REFLECTION | WP_BSDF_DELTA;
    } else {
        float u = fmin((u1 - p_specular) / (1.0f - p_specular), 0x1.fffffep-1f);
        s.direction = wp_sample_cosine_hemisphere(n, u, u2);
        float cos_o = dot(n, s.direction);
        if (!(cos_o > 0.0f)) {
            wp_bsdf_no_sample(out);
            return;
        }
        float p_diffuse = 1.0f - p_specular;
        s.weight = wp_plastic_base_pi(m, f_i, fmin(1.0f, cos_o)) / p_diffuse;
        s.pdf = p_diffuse * cos_o * (1.0f / WP_PI);
        s.flags = WP_BSDF_REFLECTION | WP_BSDF_DIFFUSE;
    }
    *out = s;
}

static inline float3 wp_plastic_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                        const WpShadingPoint* p) {
    float cos_i = fmin(1.0f, -dot(wo, p->n)), cos_o = fmin(1.0f, dot(wi, p->n));
    if (!(cos_i > 0.0f && cos_o > 0.0f))
        return (float3)(0.0f);
    float cos_t;
    return wp_plastic_base_pi(m, wp_fresnel_dielectric(cos_i, m->eta.x, &cos_t), cos_o);
}

static inline float wp_plastic_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                   const WpShadingPoint* p) {
    float cos_i = fmin(1.0f, -dot(wo, p->n)), cos_o = dot(wi, p->n);
    if (!(cos_i > 0.0f && cos_o > 0.0f))
        return 0.0f;
    float cos_t;
    float f_i = wp_fresnel_dielectric(cos_i, m->eta.x, &cos_t);
    return (1.0f - wp_plastic_specular_probability(m, f_i)) * cos_o * (1.0f / WP_PI);
}

/* Not delta as a whole: next-event estimation lights the base. */
static inline int wp_plastic_is_delta(void) {
    return 0;
}

static inline int wp_plastic_transmits(void) {
    return 0;
}

#endif /* WP_BSDF_PLASTIC_H */
