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

#endif /* WP_TEXTURES_CHECKERBOARD_H */
