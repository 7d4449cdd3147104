/* Textures: the one place that evaluates a texture by kind, and applies a
 * material's textures at a hit point.
 *
 * A textured parameter (WpMaterial.*_texture, wp_shared.h) names a texture;
 * shade replaces the parameter's constant by the texture's value at the hit
 * point's (u, v) before any BSDF sees the material, so no BSDF knows about
 * textures. The kinds are the rows of WP_TEXTURES, each behind its feature
 * switch WP_HAS_KIND_TEXTURE (scene_features.h): a scene without textures
 * compiles none of this, and shade's code is as before.
 */
#ifndef WP_TEXTURES_TEXTURE_H
#define WP_TEXTURES_TEXTURE_H

#include "scene_features.h"
#include "stage.h"
#include "textures/bitmap.h"
#include "textures/checkerboard.h"

#if WP_HAS_TEXTURES

/* The luminance of linear sRGB (Rec. 709 primaries), which Mitsuba's
 * float-valued lookups of a colour texture return (measured: eval_1 of a
 * bitmap). */
static inline float wp_luminance(float3 c) {
    return 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z;
}

/* textures[index] at texture coordinates uv (texels: the bitmaps'), as a
 * colour, or with as_float as Mitsuba looks up a float parameter (whose
 * luminance the caller takes; checkerboard.h says what differs). */
static inline float3 wp_texture_lookup(__global const WpTexture* textures,
                                       __global const wp_uint* texels, wp_uint index, float2 uv,
                                       int as_float) {
    WpTexture t = textures[index];
    float2 mapped = (float2)(t.to_u.x * uv.x + t.to_u.y * uv.y + t.to_u.z,
                             t.to_v.x * uv.x + t.to_v.y * uv.y + t.to_v.z);
#if WP_HAS_CHECKERBOARD_TEXTURE
    if (t.kind == WP_TEXTURE_CHECKERBOARD)
        return as_float ? wp_checkerboard_eval_float(&t, mapped) : wp_checkerboard_eval(&t, mapped);
#endif
#if WP_HAS_BITMAP_TEXTURE
    if (t.kind == WP_TEXTURE_BITMAP)
        return wp_bitmap_eval(texels, &t, mapped);
#endif
    (void)texels;
    return (float3)(0.0f); /* a kind compiled out: the host never lets one be met */
}

static inline float3 wp_texture_eval(const WpSceneView* scene, wp_uint index, float2 uv) {
    return wp_texture_lookup(scene->textures, scene->texels, index, uv, 0);
}

/* A float parameter: the luminance of the lookup. */
static inline float wp_texture_eval_float(const WpSceneView* scene, wp_uint index, float2 uv) {
    return wp_luminance(wp_texture_lookup(scene->textures, scene->texels, index, uv, 1));
}

/* Whether any of the material's parameters is textured (wp_apply_textures
 * has work, and the hit's texture coordinates are needed). */
static inline int wp_material_textured(const WpMaterial* m) {
    return (m->reflectance_texture | m->specular_texture | m->transmittance_texture |
            m->alpha_u_texture | m->alpha_v_texture) != 0u;
}

/* The material as it is at texture coordinates uv: each textured parameter
 * replaced by its texture's value there. Colours are clamped to [0, 1] and
 * roughness to at least 1e-4, the ranges the loader enforces on constants
 * (docs/materials.md): an HDR texel must not make a surface reflect more
 * than it receives, nor a black one a roughness the microfacet code cannot
 * take. */
static inline void wp_apply_textures(const WpSceneView* scene, float2 uv, WpMaterial* m) {
    if (m->reflectance_texture != 0u)
        m->reflectance.xyz =
            clamp(wp_texture_eval(scene, m->reflectance_texture - 1u, uv), 0.0f, 1.0f);
    if (m->specular_texture != 0u)
        m->specular.xyz = clamp(wp_texture_eval(scene, m->specular_texture - 1u, uv), 0.0f, 1.0f);
    if (m->transmittance_texture != 0u)
        m->transmittance.xyz =
            clamp(wp_texture_eval(scene, m->transmittance_texture - 1u, uv), 0.0f, 1.0f);
    if (m->alpha_u_texture != 0u)
        m->alpha_u = fmax(wp_texture_eval_float(scene, m->alpha_u_texture - 1u, uv), 1e-4f);
    if (m->alpha_v_texture != 0u)
        m->alpha_v = fmax(wp_texture_eval_float(scene, m->alpha_v_texture - 1u, uv), 1e-4f);
}

#endif /* WP_HAS_TEXTURES */

#endif /* WP_TEXTURES_TEXTURE_H */
