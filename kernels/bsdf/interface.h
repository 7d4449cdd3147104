/* What every BSDF provides (one header per material kind in kernels/bsdf/,
 * dispatched by material kind in kernels/bsdf.h):
 *
 *   void wp_KIND_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* p,
 *                       float u1, float u2, float u_lobe, WpBsdfSample* s)
 *       a direction to continue the path in, from two uniform numbers (and
 *       u_lobe, a third, for a kind that picks its lobe after its
 *       direction's microfacet normal: roughdielectric alone,
 *       wp_bsdf_samples_lobe; the others ignore it), with the flags of the
 *       lobe it came from (flags 0: no direction, the path is absorbed),
 *       written to *s. (Written through a pointer, not
 *       returned: a struct returned by value is an sret argument, and
 *       inlining one makes LLVM emit llvm.experimental.noalias.scope.decl,
 *       which Oclgrind 21.10 cannot run.)
 *   float3 wp_KIND_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
 *                          const WpShadingPoint* p)
 *       pi times the BSDF value f(wo, wi), without the cosine (0 for a
 *       delta BSDF, which no other direction can meet);
 *   float wp_KIND_pdf(const WpMaterial* m, float3 wo, float3 wi, const WpShadingPoint* p)
 *       the solid-angle density with which sample() picks wi (0 for a delta);
 *   int wp_KIND_is_delta(void)
 *       1 for a delta BSDF (a mirror), which next-event estimation skips;
 *   int wp_KIND_transmits(void)
 *       1 for a BSDF that can send light through the surface (a dielectric),
 *       whose surface a path may meet from inside a solid.
 *
 * Conventions: wo is the direction the ray travelled (towards the surface),
 * wi points away from it, and n = p->n is the unit shading normal on the side
 * the ray came from; p->front_face says which side that is (the primitive's
 * front: outside a solid), which tells a dielectric whether the ray enters or
 * leaves. Reflection leaves on n's side, transmission on the other;
 * the integrator (kernels/shade.cl) picks the side the new ray leaves by, and
 * its offset, from the sampled direction, and absorbs a sample whose
 * direction the geometric normal puts on the other side than its flags say
 * (no light leaks through shading normals). eval and pdf may assume that wi
 * lies on n's side (next-event estimation checks it with the cosine of its
 * geometry term, at the surface point, before it asks). eval returns pi f
 * rather than f so that a Lambertian BSDF's value is its reflectance exactly
 * and the integrator applies the 1/pi once, last (kernels/shade.cl); a new
 * BSDF returns pi f too.
 */
#ifndef WP_BSDF_INTERFACE_H
#define WP_BSDF_INTERFACE_H

#include "scene_features.h"
#include "wp_shared.h"

/* What a BSDF sees of the surface point: the surface record. */
typedef struct {
    float3 n;       /* unit shading normal, on the side the ray came from */
    int front_face; /* the ray came from the primitive's front side */
#if WP_HAS_ANISOTROPY
    /* Unit, perpendicular to n: dp/du made perpendicular to it (the direction
     * alpha_u runs along; bsdf/frame.h). */
    float3 tangent;
#endif
} WpShadingPoint;

typedef struct {
    float3 direction; /* wi, unit */
    float3 weight;    /* f cos / pdf: the factor the path's throughput takes */
    float pdf;        /* solid-angle density of direction; 0 for a delta BSDF */
    wp_uint flags;    /* WP_BSDF_* (wp_shared.h): side and lobe; 0 when nothing was sampled */
    float eta;        /* relative index of refraction across the surface (1 for reflection) */
} WpBsdfSample;

/* A sample that continues nothing: the path is absorbed. */
static inline void wp_bsdf_no_sample(WpBsdfSample* s) {
    s->direction = (float3)(0.0f, 0.0f, 1.0f);
    s->weight = (float3)(0.0f);
    s->pdf = 0.0f;
    s->flags = 0u;
    s->eta = 1.0f;
}

static inline int wp_bsdf_sample_is_delta(const WpBsdfSample* s) {
    return (s->flags & WP_BSDF_DELTA) != 0u;
}

#endif /* WP_BSDF_INTERFACE_H */
