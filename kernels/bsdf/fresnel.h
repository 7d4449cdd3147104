/* Fresnel reflectance of a conductor. */
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

/* A conductor material's Fresnel term at incidence cosine cos_theta, times its
 * specular_reflectance (material "none": F = 1). */
static inline float3 wp_conductor_reflectance(const WpMaterial* m, float cos_theta) {
    float3 f = m->fresnel ? wp_fresnel_conductor(cos_theta, m->eta.xyz, m->k.xyz) : (float3)(1.0f);
    return f * m->reflectance.xyz;
}

#endif /* WP_BSDF_FRESNEL_H */
