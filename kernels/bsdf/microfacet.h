/* Microfacet distributions as Mitsuba 3 defines them (its
 * render/microfacet.h): Beckmann and GGX, isotropic or anisotropic (alpha_u
 * along the tangent, alpha_v along the bitangent), with Smith's separable
 * shadowing-masking G(wi, wo, m) = G1(wi, m) G1(wo, m), and sampling of the
 * normals visible from a direction.
 *
 * Everything is in the local frame: z along the (shading) normal, vectors
 * unit. A WpMicrofacet's alphas are the material's, bounded below by
 * WP_MICROFACET_MIN_ALPHA so that D stays finite in float (the loader
 * rejects alpha <= 0; Mitsuba clamps at the same 1e-4).
 *
 * Sampling (wp_microfacet_sample_visible) draws m with density
 *     D_wi(m) = G1(wi, m) max(0, dot(wi, m)) D(m) / cos_theta(wi)
 * (Heitz and d'Eon, "Importance Sampling Microfacet-Based BSDFs using the
 * Distribution of Visible Normals", 2014): for GGX by Heitz's exact
 * construction ("Sampling the GGX Distribution of Visible Normals", JCGT
 * 2018), for Beckmann by stretching to alpha 1 and inverting the slope CDF
 * with Newton's method (Jakob, "An Improved Visible Normal Sampling Routine
 * for the Beckmann Distribution", 2014, in Mitsuba 3's form).
 */
#ifndef WP_BSDF_MICROFACET_H
#define WP_BSDF_MICROFACET_H

#include "sampling.h"
#include "wp_shared.h"

#define WP_MICROFACET_MIN_ALPHA 1e-4f

typedef struct {
    float alpha_u, alpha_v;
    wp_uint distribution; /* WP_MICROFACET_* */
} WpMicrofacet;

/* w in the local frame (t, b, n) of a microfacet BSDF, t and b from
 * wp_make_basis(n). */
static inline float3 wp_to_local(float3 w, float3 n) {
    float3 t, b;
    wp_make_basis(n, &t, &b);
    return (float3)(dot(w, t), dot(w, b), dot(w, n));
}

/* The material's distribution, written through a pointer as every struct the
 * shade kernel inlines is (a returned one is an sret argument, which
 * Oclgrind 21.10 cannot run once inlined: bsdf/interface.h). */
static inline void wp_microfacet_of(const WpMaterial* m, WpMicrofacet* d) {
    d->alpha_u = fmax(m->alpha_u, WP_MICROFACET_MIN_ALPHA);
    d->alpha_v = fmax(m->alpha_v, WP_MICROFACET_MIN_ALPHA);
    d->distribution = m->distribution;
}

/* The distribution of normals D(m), per unit projected area. */
static inline float wp_microfacet_d(const WpMicrofacet* d, float3 m) {
    if (!(m.z > 0.0f))
        return 0.0f;
    float x = m.x / d->alpha_u, y = m.y / d->alpha_v, z2 = m.z * m.z;
    float area = WP_PI * d->alpha_u * d->alpha_v;
    float result;
    if (d->distribution == WP_MICROFACET_GGX) {
        float s = x * x + y * y + z2;
        result = 1.0f / (area * s * s);
    } else {
        result = exp(-(x * x + y * y) / z2) / (area * z2 * z2);
    }
    /* Far from the normal exp and the powers may underflow together: 0, not NaN. */
    return isfinite(result) ? result : 0.0f;
}

/* Smith's masking G1(v, m) of the direction v for microfacet normal m
 * (Mitsuba's smith_g1: Walter et al.'s rational fit for Beckmann). */
static inline float wp_microfacet_g1(const WpMicrofacet* d, float3 v, float3 m) {
    if (!(dot(v, m) * v.z > 0.0f))
        return 0.0f; /* the back of a microfacet is never seen */
    float ax = d->alpha_u * v.x, ay = d->alpha_v * v.y;
    float xy_alpha_2 = ax * ax + ay * ay;
    if (xy_alpha_2 == 0.0f)
        return 1.0f; /* perpendicular incidence */
    float tan_theta_alpha_2 = xy_alpha_2 / (v.z * v.z);
    if (d->distribution == WP_MICROFACET_GGX)
        return 2.0f / (1.0f + sqrt(1.0f + tan_theta_alpha_2));
    float a = rsqrt(tan_theta_alpha_2);
    if (a >= 1.6f)
        return 1.0f;
    return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

/* The inverse error function in single precision (Giles, "Approximating the
 * erfinv function", GPU Computing Gems Jade Edition, 2011), for x in (-1, 1). */
static inline float wp_erfinv(float x) {
    float w = -log((1.0f - x) * (1.0f + x));
    float p;
    if (w < 5.0f) {
        w = w - 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = sqrt(w) - 3.0f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    return p * x;
}

/* Beckmann with alpha 1: the slopes of the normals visible from a direction
 * of cosine cos_theta (> 0) in the plane x-z, from two uniform numbers. */
static inline float2 wp_beckmann_visible_slope(float cos_theta, float u1, float u2) {
    const float sqrt_pi_inv = 0.564189583547756f;
    cos_theta = fmax(cos_theta, 1e-6f);
    float tan_theta = sqrt(fmax(0.0f, 1.0f - cos_theta * cos_theta)) / cos_theta;
    float cot_theta = 1.0f / tan_theta;
    float maxval = erf(cot_theta);
    u1 = clamp(u1, 1e-6f, 1.0f - 1e-6f);
    u2 = clamp(u2, 1e-6f, 1.0f - 1e-6f);
    /* Mitsuba's initial guess, then three Newton steps on the slope CDF. */
    float x = maxval - (maxval + 1.0f) * erf(sqrt(-log(u1)));
    float target = u1 * (1.0f + maxval + sqrt_pi_inv * tan_theta * exp(-cot_theta * cot_theta));
    for (int i = 0; i < 3; ++i) {
        float slope = wp_erfinv(clamp(x, -0.99999994f, 0.99999994f));
        float value = 1.0f + x + sqrt_pi_inv * tan_theta * exp(-slope * slope) - target;
        float derivative = 1.0f - slope * tan_theta;
        x -= value / derivative;
    }
    return (float2)(wp_erfinv(clamp(x, -0.99999994f, 0.99999994f)), wp_erfinv(2.0f * u2 - 1.0f));
}

/* A normal m drawn from the normals visible from wi (wi.z > 0), with
 * density D_wi(m) (wp_microfacet_pdf_visible). */
static inline float3 wp_microfacet_sample_visible(const WpMicrofacet* d, float3 wi, float u1,
                                                  float u2) {
    /* Stretch to the alpha-1 configuration. */
    float3 v = normalize((float3)(d->alpha_u * wi.x, d->alpha_v * wi.y, wi.z));
    if (d->distribution == WP_MICROFACET_GGX) {
        /* Heitz 2018: a point on the projected hemisphere, uniform over the
         * disk, with the half-disk behind v squashed by its visible part. */
        float lensq = v.x * v.x + v.y * v.y;
        float3 t1 =
            lensq > 0.0f ? (float3)(-v.y, v.x, 0.0f) * rsqrt(lensq) : (float3)(1.0f, 0.0f, 0.0f);
        float3 t2 = cross(v, t1);
        float r = sqrt(u1);
        float s_phi, c_phi;
        wp_sincos_2pi(u2, &s_phi, &c_phi);
        float p1 = r * c_phi;
        float p2 = r * s_phi;
        float s = 0.5f * (1.0f + v.z);
        p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * p2;
        float3 nh = p1 * t1 + p2 * t2 + sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
        return normalize((float3)(d->alpha_u * nh.x, d->alpha_v * nh.y, fmax(0.0f, nh.z)));
    }
    float sin_theta = sqrt(v.x * v.x + v.y * v.y);
    float cos_phi = sin_theta > 0.0f ? clamp(v.x / sin_theta, -1.0f, 1.0f) : 1.0f;
    float sin_phi = sin_theta > 0.0f ? clamp(v.y / sin_theta, -1.0f, 1.0f) : 0.0f;
    float2 slope = wp_beckmann_visible_slope(v.z, u1, u2);
    /* Rotate to wi's azimuth, unstretch. */
    float sx = (cos_phi * slope.x - sin_phi * slope.y) * d->alpha_u;
    float sy = (sin_phi * slope.x + cos_phi * slope.y) * d->alpha_v;
    return normalize((float3)(-sx, -sy, 1.0f));
}

/* The density of wp_microfacet_sample_visible's m, given wi. */
static inline float wp_microfacet_pdf_visible(const WpMicrofacet* d, float3 wi, float3 m) {
    if (!(wi.z > 0.0f))
        return 0.0f;
    return wp_microfacet_d(d, m) * wp_microfacet_g1(d, wi, m) * fabs(dot(wi, m)) / wi.z;
}

#endif /* WP_BSDF_MICROFACET_H */
