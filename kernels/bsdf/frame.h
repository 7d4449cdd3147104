/* The local frame (tangent, bitangent, n) of a microfacet BSDF, in which
 * alpha_u is the roughness along the tangent and alpha_v along the
 * bitangent (bsdf/microfacet.h).
 *
 * An anisotropic material (alpha_u != alpha_v, after its textures) takes the
 * surface's tangent: dp/du (tangent.h) made perpendicular to the shading
 * normal by Gram-Schmidt, t = normalize(dp_du - n dot(n, dp_du)), as Mitsuba
 * 3.9.1 builds its shading frame (SurfaceInteraction::initialize_sh_frame),
 * so that its highlight runs the way Mitsuba's does; the bitangent is
 * cross(n, t). Where dp/du is 0 or along n (a sphere's poles) the tangent
 * falls back to wp_make_basis(n), as Mitsuba's falls back to
 * coordinate_system(n). n is on the side the ray came from (Mitsuba keeps
 * the front one); the bitangent's sign follows it, which no microfacet
 * distribution can tell, being symmetric under (x, y) -> (x, -y).
 *
 * An isotropic material keeps wp_make_basis(n): any frame about n gives it
 * the same distribution, and this one keeps its images bit for bit what they
 * were without the tangent (the general kernels compile it in too). Without
 * WP_HAS_ANISOTROPY (no anisotropic material in the scene) nothing of the
 * tangent is compiled. */
#ifndef WP_BSDF_FRAME_H
#define WP_BSDF_FRAME_H

#include "bsdf/interface.h"
#include "sampling.h"

#if WP_HAS_ANISOTROPY
/* p->tangent from dp/du and p->n. */
static inline void wp_shading_tangent(float3 dp_du, WpShadingPoint* p) {
    float3 t = dp_du - dot(p->n, dp_du) * p->n;
    float length2 = dot(t, t);
    /* Relative to dp/du's length: 0, or within rounding of n. */
    if (length2 > 1e-10f * dot(dp_du, dp_du) && length2 > 0.0f) {
        p->tangent = t * rsqrt(length2);
    } else {
        float3 b;
        wp_make_basis(p->n, &p->tangent, &b);
    }
}
#endif

static inline void wp_bsdf_frame(const WpMaterial* m, const WpShadingPoint* p, float3* t,
                                 float3* b) {
#if WP_HAS_ANISOTROPY
    if (m->alpha_u != m->alpha_v) {
        *t = p->tangent;
        *b = cross(p->n, p->tangent);
        return;
    }
#endif
    (void)m;
    wp_make_basis(p->n, t, b);
}

/* w in the frame of wp_bsdf_frame. */
static inline float3 wp_bsdf_to_local(const WpMaterial* m, const WpShadingPoint* p, float3 w) {
    float3 t, b;
    wp_bsdf_frame(m, p, &t, &b);
    return (float3)(dot(w, t), dot(w, b), dot(w, p->n));
}

#endif /* WP_BSDF_FRAME_H */
