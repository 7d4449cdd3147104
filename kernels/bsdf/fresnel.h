/* Fresnel reflectance of a conductor and of a dielectric interface. */
#ifndef WP_BSDF_FRESNEL_H
#define WP_BSDF_FRESNEL_H

#include "wp_shared.h"

/* The unpolarised reflectance at incidence cosine cos_theta (in [0, 1]) of a
 * conductor of complex relative index eta + i k, per channel: Mitsuba 3's
 * fresnel_conductor (render/fresnel.h), after K. D. Moeller, "Optics" (1988).
 * eta = 0, k > 0 reflects everything (R = 1 exactly); eta = 1, k = 0 is no
 * interface (R = 0 away from grazing). */
static inline float3 wp_fresnel_conductor(float cos_theta, float3 eta, float3 k) {
    float cos2 = cos_theta * cos_theta;
    float sin2 = 1.0f - cos2;
    float sin4 = sin2 * sin2;
    float3 temp1 = eta * eta - k * k - sin2;
    float3 a2pb2 = sqrt(temp1 * temp1 + 4.0f * k * k * eta * eta);
    float3 a = sqrt(fmax(0.5f * (a2pb2 + temp1), 0.0f));
    float3 term1 = a2pb2 + cos2;
    float3 term2 = (2.0f * cos_theta) * a;
    float3 rs = (term1 - term2) / (term1 + term2);
    float3 term3 = a2pb2 * cos2 + sin4;
    float3 term4 = term2 * sin2;
    float3 rp = rs * (term3 - term4) / (term3 + term4);
    float3 r = 0.5f * (rs + rp);
    /* 0 / 0 only for a vanishing interface at grazing incidence: nothing reflects. */
    return select((float3)(0.0f), clamp(r, 0.0f, 1.0f), isfinite(r));
}

/* The unpolarised reflectance of a dielectric interface for light arriving at
 * incidence cosine cos_i (in [0, 1], on the side it comes from) where the
 * index of refraction relative to that side is eta (n_other / n_this, > 0):
 * Mitsuba 3's fresnel (render/fresnel.h), without its sign conventions.
 * *cos_t is the cosine of the refracted direction on the other side (>= 0; 0
 * under total internal reflection, where R = 1). eta = 1 is no interface (R
 * = 0 exactly, also at grazing incidence); cos_i = 0 reflects everything. */
static inline float wp_fresnel_dielectric(float cos_i, float eta, float* cos_t) {
    float inv_eta = 1.0f / eta;
    float cos_t2 = 1.0f - (1.0f - cos_i * cos_i) * (inv_eta * inv_eta);
    *cos_t = sqrt(fmax(cos_t2, 0.0f));
    if (eta == 1.0f)
        return 0.0f;
    if (!(cos_i > 0.0f) || !(cos_t2 > 0.0f))
        return 1.0f;
    float a_s = (cos_i - eta * *cos_t) / (cos_i + eta * *cos_t);
    float a_p = (*cos_t - eta * cos_i) / (*cos_t + eta * cos_i);
    return clamp(0.5f * (a_s * a_s + a_p * a_p), 0.0f, 1.0f);
}

/* A conductor material's Fresnel term at incidence cosine cos_theta, times its
 * specular_reflectance (material "none": F = 1). */
static inline float3 wp_conductor_reflectance(const WpMaterial* m, float cos_theta) {
    float3 f = m->fresnel ? wp_fresnel_conductor(cos_theta, m->eta.xyz, m->k.xyz) : (float3)(1.0f);
    return f * m->reflectance.xyz;
}

#endif /* WP_BSDF_FRESNEL_H */
