/* Materials: the one place that selects a BSDF by material kind.
 *
 * Material kinds (WpMaterial.kind, WP_MATERIAL_* in wp_shared.h):
 *   diffuse   Lambertian, kernels/bsdf/diffuse.h
 *   mirror    perfect specular reflection, kernels/bsdf/mirror.h (compiled
 *             only with WP_HAS_MIRROR)
 *   emitter   emits (WpMaterial.emission, front face) and scatters nothing:
 *             a path ends there
 * Diffuse is the fallback, so a kind compiled out of a program can never be
 * met by it (the scene's features decide what is compiled,
 * src/render/device_scene.cpp). docs/architecture.md lists what a new kind
 * touches.
 */
#ifndef WP_BSDF_H
#define WP_BSDF_H

#include "bsdf/diffuse.h"
#include "bsdf/mirror.h"
#include "scene_features.h"

/* 1 if the material scatters no light at all (its path ends). */
static inline int wp_bsdf_is_black(const WpMaterial* m) {
    return m->kind == WP_MATERIAL_EMITTER;
}

/* Returns wp_KIND_FUNCTION(...) of the material's kind: the one place that
 * selects a BSDF. A new kind is one more line here, guarded by its feature
 * switch (a constant, so the test folds away when the kind is compiled out). */
#define WP_BSDF_DISPATCH(m, function, ...)                                                         \
    if (WP_HAS_MIRROR && (m)->kind == WP_MATERIAL_MIRROR)                                          \
        return wp_mirror_##function(__VA_ARGS__);                                                  \
    return wp_diffuse_##function(__VA_ARGS__)

/* 1 for a delta BSDF: light can reach it only along its sampled direction. */
static inline int wp_bsdf_is_delta(const WpMaterial* m) {
    WP_BSDF_DISPATCH(m, is_delta, );
}

static inline WpBsdfSample wp_bsdf_sample(const WpMaterial* m, float3 wo, float3 n, float u1,
                                          float u2) {
    WP_BSDF_DISPATCH(m, sample, m, wo, n, u1, u2);
}

static inline float3 wp_bsdf_eval_pi(const WpMaterial* m, float3 wo, float3 wi, float3 n) {
    WP_BSDF_DISPATCH(m, eval_pi, m, wo, wi, n);
}

static inline float wp_bsdf_pdf(const WpMaterial* m, float3 wo, float3 wi, float3 n) {
    WP_BSDF_DISPATCH(m, pdf, m, wo, wi, n);
}

#endif /* WP_BSDF_H */
