/* Materials: the one place that selects a BSDF by material kind.
 *
 * The kinds are the rows of WP_MATERIALS (wp_shared.h); a row with a BSDF
 * has its header kernels/bsdf/NAME.h, included below, and is dispatched to
 * when its feature switch WP_HAS_KIND (scene_features.h) is on. The emitter
 * has no BSDF: it emits (WpMaterial.emission, front face) and scatters
 * nothing, so a path ends there. Diffuse is the fallback, so a kind compiled
 * out of a program can never be met by it (the scene's features decide what
 * is compiled, src/render/device_scene.cpp). docs/architecture.md lists what
 * a new kind touches.
 */
#ifndef WP_BSDF_H
#define WP_BSDF_H

#include "bsdf/conductor.h"
#include "bsdf/dielectric.h"
#include "bsdf/diffuse.h"
#include "bsdf/mirror.h"
#include "bsdf/plastic.h"
#include "bsdf/roughconductor.h"
#include "bsdf/roughdielectric.h"
#include "bsdf/roughplastic.h"
#include "bsdf/thindielectric.h"
#include "scene_features.h"

/* 1 if the material scatters no light at all (its path ends). */
static inline int wp_bsdf_is_black(const WpMaterial* m) {
    return m->kind == WP_MATERIAL_EMITTER;
}

/* wp_bsdf_FUNCTION returns wp_NAME_FUNCTION(...) of the material's kind: one
 * test per row of WP_MATERIALS with a BSDF, guarded by its feature switch (a
 * constant, so the test folds away when the kind is compiled out), and
 * diffuse as the fallback. `call` is FUNCTION(arguments). */
#define WP_BSDF_TRY(KIND, name, bsdf, call)                                                        \
    WP_IF(bsdf)(if (WP_HAS_##KIND && m->kind == WP_MATERIAL_##KIND) return wp_##name##_##call;)

/* The same for a function that writes its result through a pointer (C has no
 * `return` of a void expression). */
#define WP_BSDF_TRY_WRITE(KIND, name, bsdf, call)                                                  \
    WP_IF(bsdf)                                                                                    \
    (if (WP_HAS_##KIND && m->kind == WP_MATERIAL_##KIND) {                                         \
        wp_##name##_##call;                                                                        \
        return;                                                                                    \
    })

/* 1 for a delta BSDF: light can reach it only along its sampled direction. */
#define WP_BSDF_IS_DELTA_ROW(KIND, Name, name, value, bsdf, glossy)                                \
    WP_BSDF_TRY(KIND, name, bsdf, is_delta())
static inline int wp_bsdf_is_delta(const WpMaterial* m) {
    WP_MATERIALS(WP_BSDF_IS_DELTA_ROW)
    return wp_diffuse_is_delta();
}

/* 1 for a BSDF that can send light through the surface: a path may meet its
 * surface from inside a solid. */
#define WP_BSDF_TRANSMITS_ROW(KIND, Name, name, value, bsdf, glossy)                               \
    WP_BSDF_TRY(KIND, name, bsdf, transmits())
static inline int wp_bsdf_transmits(const WpMaterial* m) {
    WP_MATERIALS(WP_BSDF_TRANSMITS_ROW)
    return wp_diffuse_transmits();
}

#define WP_BSDF_SAMPLE_ROW(KIND, Name, name, value, bsdf, glossy)                                  \
    WP_BSDF_TRY_WRITE(KIND, name, bsdf, sample(m, wo, p, u1, u2, u_lobe, s))
static inline void wp_bsdf_sample(const WpMaterial* m, float3 wo, const WpShadingPoint* p, float u1,
                                  float u2, float u_lobe, WpBsdfSample* s) {
    WP_MATERIALS(WP_BSDF_SAMPLE_ROW)
    wp_diffuse_sample(m, wo, p, u1, u2, u_lobe, s);
}

/* 1 for a kind whose sample reads its third number, u_lobe (only
 * roughdielectric): the caller draws that number only then, so that no other
 * path pays for it. */
static inline int wp_bsdf_samples_lobe(const WpMaterial* m) {
    return WP_HAS_ROUGHDIELECTRIC && m->kind == WP_MATERIAL_ROUGHDIELECTRIC;
}

#define WP_BSDF_EVAL_ROW(KIND, Name, name, value, bsdf, glossy)                                    \
    WP_BSDF_TRY(KIND, name, bsdf, eval_pi(m, wo, wi, p))
static inline float3 wp_bsdf_eval_pi(const WpMaterial* m, float3 wo, float3 wi,
                                     const WpShadingPoint* p) {
    WP_MATERIALS(WP_BSDF_EVAL_ROW)
    return wp_diffuse_eval_pi(m, wo, wi, p);
}

#define WP_BSDF_PDF_ROW(KIND, Name, name, value, bsdf, glossy)                                     \
    WP_BSDF_TRY(KIND, name, bsdf, pdf(m, wo, wi, p))
static inline float wp_bsdf_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                const WpShadingPoint* p) {
    WP_MATERIALS(WP_BSDF_PDF_ROW)
    return wp_diffuse_pdf(m, wo, wi, p);
}

/* pi f and (into *pdf) the density of wi together, as next-event estimation
 * needs them: the kinds whose one evaluation yields both (roughdielectric,
 * roughplastic) evaluate once instead of twice; every other kind is
 * wp_bsdf_eval_pi and wp_bsdf_pdf. The same floats as the two calls. */
static inline float3 wp_bsdf_eval_pi_pdf(const WpMaterial* m, float3 wo, float3 wi,
                                         const WpShadingPoint* p, float* pdf) {
    if (WP_HAS_ROUGHPLASTIC && m->kind == WP_MATERIAL_ROUGHPLASTIC)
        return wp_roughplastic_eval_pi_pdf(m, wo, wi, p, pdf);
    if (WP_HAS_ROUGHDIELECTRIC && m->kind == WP_MATERIAL_ROUGHDIELECTRIC)
        return wp_roughdielectric_eval_pi_pdf(m, wo, wi, p, pdf);
    *pdf = wp_bsdf_pdf(m, wo, wi, p);
    return wp_bsdf_eval_pi(m, wo, wi, p);
}

/* Whether the program has a glossy kind (the glossy column of WP_MATERIALS):
 * a constant for #if. */
#define WP_GLOSSY_TERM(KIND, Name, name, value, bsdf, glossy) WP_IF(glossy)(|| WP_HAS_##KIND)
#define WP_HAS_GLOSSY (0 WP_MATERIALS(WP_GLOSSY_TERM))

/* Whether next-event estimation is weighed against BSDF sampling at every
 * vertex that is not delta (a Lambertian one too), as Mitsuba 3's path
 * integrator does: with the power heuristic (--mis power, the default) and
 * cosine-weighted diffuse directions. The report's estimator
 * (WP_DIFFUSE_REPORT) keeps pure light sampling at Lambertian vertices, as its
 * images were made, and --mis light keeps it everywhere (lights.h gives its
 * weights: 1 and 0). A constant for #if. */
#define WP_MIS_EVERY_VERTEX                                                                        \
    (WP_MIS_STRATEGY == WP_MIS_POWER && WP_DIFFUSE_SAMPLING == WP_DIFFUSE_COSINE)

/* Whether the program has vertices where light samples and BSDF samples are
 * weighed against each other (kernels/shade.cl): a constant for #if. */
#define WP_HAS_WEIGHED_VERTICES (WP_HAS_GLOSSY || WP_MIS_EVERY_VERTEX)

/* 1 where next-event estimation is weighed against BSDF sampling by multiple
 * importance sampling (kernels/shade.cl): every kind that is not delta with
 * WP_MIS_EVERY_VERTEX, else the glossy kinds. Elsewhere a non-delta vertex
 * keeps pure light sampling (emission its sampled rays find does not count);
 * a delta one has no next event. */
#define WP_GLOSSY_KIND(KIND, Name, name, value, bsdf, glossy)                                      \
    WP_IF(glossy)(if (WP_HAS_##KIND && m->kind == WP_MATERIAL_##KIND) return 1;)
static inline int wp_bsdf_weighs_light(const WpMaterial* m) {
#if WP_MIS_EVERY_VERTEX
    return !wp_bsdf_is_delta(m);
#else
    WP_MATERIALS(WP_GLOSSY_KIND)
    (void)m;
    return 0;
#endif
}

#endif /* WP_BSDF_H */
