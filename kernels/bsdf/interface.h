/* What every BSDF provides (one header per material kind in kernels/bsdf/,
 * dispatched by material kind in kernels/bsdf.h):
 *
 *   WpBsdfSample wp_KIND_sample(const WpMaterial* m, float3 wo, float3 n,
 *                               float u1, float u2)
 *       a direction to continue the path in, from two uniform numbers;
 *   float3 wp_KIND_eval_pi(const WpMaterial* m, float3 wo, float3 wi, float3 n)
 *       pi times the BSDF value f(wo, wi), without the cosine (0 for a
 *       delta BSDF, which no other direction can meet);
 *   float wp_KIND_pdf(const WpMaterial* m, float3 wo, float3 wi, float3 n)
 *       the solid-angle density with which sample() picks wi (0 for a delta);
 *   int wp_KIND_is_delta(void)
 *       1 for a delta BSDF (a mirror), which next-event estimation skips.
 *
 * Conventions: wo is the direction the ray travelled (towards the surface),
 * wi points away from it, and n is the unit geometric normal on the side the
 * ray came from; eval and pdf may assume that wi lies on n's side (next-event
 * estimation checks it with the cosine of its geometry term, at the surface
 * point, before it asks). eval returns pi f rather than f so that a Lambertian BSDF's
 * value is its reflectance exactly and the integrator applies the 1/pi once,
 * last (kernels/shade.cl); a new BSDF returns pi f too.
 */
#ifndef WP_BSDF_INTERFACE_H
#define WP_BSDF_INTERFACE_H

#include "wp_shared.h"

typedef struct {
    float3 direction; /* wi, unit */
    float3 weight;    /* f cos / pdf: the factor the path's throughput takes */
    float pdf;        /* solid-angle density of direction; 0 for a delta BSDF */
    int specular;     /* a delta BSDF: next-event estimation cannot reach it */
} WpBsdfSample;

#endif /* WP_BSDF_INTERFACE_H */
