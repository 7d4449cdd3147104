/* Mitsuba 3's `checkerboard` texture: squares of side 1/2 in (u', v'),
 * color0 where u' and v' fall in the same half of their unit interval
 * ((u' mod 1 < 1/2) == (v' mod 1 < 1/2)), color1 elsewhere; repeating
 * without end (measured with Mitsuba's plugin, tests/kernels/test_textures.cpp).
 */
#ifndef WP_TEXTURES_CHECKERBOARD_H
#define WP_TEXTURES_CHECKERBOARD_H

#include "wp_shared.h"

static inline float3 wp_checkerboard_eval(const WpTexture* t, float2 uv) {
    /* x - floor(x) is in [0, 1] (1 only by rounding of a tiny negative x). */
    int u_low = uv.x - floor(uv.x) < 0.5f;
    int v_low = uv.y - floor(uv.y) < 0.5f;
    return u_low == v_low ? t->color0.xyz : t->color1.xyz;
}

/* The same as a float (a roughness). Mitsuba 3.9.1's checkerboard gives the
 * other colour there: its eval_1 returns color1 where its eval returns color0
 * (measured: to_uv scale (4, 2), color0 0.05, color1 0.4, at uv (0.1, 0.1)
 * eval is 0.05, eval_1 0.4). wavepath follows it, so that a Mitsuba scene's
 * rough surfaces are rough where Mitsuba renders them rough. */
static inline float3 wp_checkerboard_eval_float(const WpTexture* t, float2 uv) {
    int u_low = uv.x - floor(uv.x) < 0.5f;
    int v_low = uv.y - floor(uv.y) < 0.5f;
    return u_low == v_low ? t->color1.xyz : t->color0.xyz;
}

#endif /* WP_TEXTURES_CHECKERBOARD_H */
