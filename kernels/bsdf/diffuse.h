/* The Lambertian BSDF: f = reflectance / pi on the side the ray came from.
 *
 * Its sample() follows WP_DIFFUSE_SAMPLING (estimator.h):
 *   WP_DIFFUSE_COSINE: cosine-weighted directions, pdf cos / pi, so the
 *     weight f cos / pdf is the reflectance;
 *   WP_DIFFUSE_REPORT: the student report's uniform (theta, phi) with its
 *     albedo roulette folded into theta: theta' = u1 pi/2, and the roulette
 *     (kernels/shade.cl) ends the path when theta' > sigma pi/2, i.e. when
 *     u1 >= sigma; a survivor goes on at theta = theta' / sigma, uniform in
 *     [0, pi/2] again. (theta, phi) uniform in the rectangle has solid-angle
 *     pdf 1 / (pi^2 sin theta), so the weight is pi rho cos sin.
 */
#ifndef WP_BSDF_DIFFUSE_H
#define WP_BSDF_DIFFUSE_H

#include "bsdf/interface.h"
#include "color.h"
#include "estimator.h"
#include "sampling.h"

/* Always inlined: left a call, it took the material by address, so shade
 * copied its whole WpMaterial (416 bytes, memcpy) to private memory for every
 * path it shaded (the hexroom's stage kernel; docs/performance.md, "The
 * plain scenes' shade, cut"). */
static inline WP_ALWAYS_INLINE void wp_diffuse_sample(const WpMaterial* m, float3 wo,
                                                      const WpShadingPoint* point, float u1,
                                                      float u2, float u_lobe, WpBsdfSample* out) {
    (void)u_lobe; /* roughdielectric's alone (bsdf/interface.h) */
    float3 n = point->n;
    (void)wo;
    WpBsdfSample s;
    float3 reflectance = m->reflectance.xyz;
#if WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT
    float sigma = fmin(1.0f, wp_max_component(reflectance));
    float theta = (sigma > 0.0f ? fmin(1.0f, u1 / sigma) : 0.0f) * (0.5f * WP_PI);
    s.direction = wp_direction_from_angles(n, theta, 2.0f * WP_PI * u2);
    s.weight = reflectance * (WP_PI * cos(theta) * sin(theta));
    s.pdf = 1.0f / (WP_PI * WP_PI * sin(theta));
#else
    s.direction = wp_sample_cosine_hemisphere(n, u1, u2);
    s.weight = reflectance;
    s.pdf = fmax(dot(n, s.direction), 0.0f) * (1.0f / WP_PI);
#endif
    s.flags = WP_BSDF_REFLECTION | WP_BSDF_DIFFUSE;
    s.eta = 1.0f;
    *out = s;
}

static inline float3 wp_diffuse_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                        const WpShadingPoint* point) {
    (void)point;
    (void)wo;
    (void)wi;
    return m->reflectance.xyz;
}

static inline float wp_diffuse_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                   const WpShadingPoint* point) {
    float3 n = point->n;
    (void)m;
    (void)wo;
    float cos_theta = dot(n, wi);
    if (!(cos_theta > 0.0f))
        return 0.0f;
#if WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT
    float sin_theta = sqrt(fmax(0.0f, 1.0f - cos_theta * cos_theta));
    return 1.0f / (WP_PI * WP_PI * sin_theta);
#else
    return cos_theta * (1.0f / WP_PI);
#endif
}

/* Not a delta BSDF: next-event estimation applies. */
static inline int wp_diffuse_is_delta(void) {
    return 0;
}

static inline int wp_diffuse_transmits(void) {
    return 0;
}

#endif /* WP_BSDF_DIFFUSE_H */
