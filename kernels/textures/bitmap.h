/* Mitsuba 3's `bitmap` texture: an image, looked up at (u', v') after the
 * texture's transform (WpTexture, wp_shared.h).
 *
 * Texel (x, y) covers [x, x + 1) / width by [y, y + 1) / height, row 0 at
 * v' = 0. Bilinear filtering blends the four texels around
 * (u' width - 1/2, v' height - 1/2), nearest takes the texel under
 * (u' width, v' height); indices outside the image wrap by the texture's
 * wrap mode: repeat (modulo the size), mirror (every other copy reversed)
 * or clamp (the edge texel). These are Mitsuba's conventions, measured with
 * its bitmap plugin (tests/kernels/test_textures.cpp checks against them).
 * Blending happens in linear RGB: sRGB-encoded texels are decoded first, as
 * Mitsuba decodes a whole 8-bit file when it loads it.
 */
#ifndef WP_TEXTURES_BITMAP_H
#define WP_TEXTURES_BITMAP_H

#include "textures/srgb8.h"
#include "wp_shared.h"

/* sRGB's decoding curve (IEC 61966-2-1); 8-bit texels take it from the
 * table of its values instead (textures/srgb8.h). */
static inline float wp_srgb_to_linear(float c) {
    return c <= 0.04045f ? c * (1.0f / 12.92f) : pow((c + 0.055f) * (1.0f / 1.055f), 2.4f);
}

/* Texel index i of a row or column of n texels, wrapped into [0, n). */
static inline int wp_wrap_texel(int i, int n, wp_uint wrap) {
    if (wrap == WP_TEXTURE_WRAP_CLAMP)
        return clamp(i, 0, n - 1);
    if (wrap == WP_TEXTURE_WRAP_MIRROR) {
        /* Period 2n: the image, then its mirror image. */
        int m = i % (2 * n);
        m = m < 0 ? m + 2 * n : m;
        return m < n ? m : 2 * n - 1 - m;
    }
    int m = i % n;
    return m < 0 ? m + n : m;
}

/* A texture position in texels, kept where the conversion to int is defined.
 * Past 2^23 a float has no fraction left, so which texel a position that
 * large picks does not matter; a NaN position becomes the bound (fmax returns
 * its other operand), so no NaN reaches the index arithmetic. */
static inline float wp_texel_position(float x) {
    return fmin(fmax(x, -8388608.0f), 8388608.0f);
}

/* The linear RGB value of texel (x, y), both in range. */
static inline float3 wp_bitmap_texel(__global const wp_uint* texels, const WpTexture* t, int x,
                                     int y) {
    wp_uint i = (wp_uint)y * t->width + (wp_uint)x;
    if (t->format == WP_TEXELS_RGB32F) {
        __global const wp_uint* p = texels + t->first + 3u * i;
        return (float3)(as_float(p[0]), as_float(p[1]), as_float(p[2]));
    }
    wp_uint bits = texels[t->first + i];
    if (t->format == WP_TEXELS_RGBA8_SRGB)
        return (float3)(wp_srgb8_to_linear[bits & 255u], wp_srgb8_to_linear[(bits >> 8) & 255u],
                        wp_srgb8_to_linear[(bits >> 16) & 255u]);
    return (float3)((float)(bits & 255u), (float)((bits >> 8) & 255u),
                    (float)((bits >> 16) & 255u)) *
           (1.0f / 255.0f);
}

static inline float3 wp_bitmap_eval(__global const wp_uint* texels, const WpTexture* t, float2 uv) {
    int w = (int)t->width, h = (int)t->height;
    if (t->filter == WP_TEXTURE_FILTER_NEAREST) {
        int x = (int)floor(wp_texel_position(uv.x * (float)w));
        int y = (int)floor(wp_texel_position(uv.y * (float)h));
        return wp_bitmap_texel(texels, t, wp_wrap_texel(x, w, t->wrap),
                               wp_wrap_texel(y, h, t->wrap));
    }
    float x = wp_texel_position(uv.x * (float)w - 0.5f);
    float y = wp_texel_position(uv.y * (float)h - 0.5f);
    float x_floor = floor(x), y_floor = floor(y);
    float ax = x - x_floor, ay = y - y_floor; /* weights of the second column and row */
    int x0 = (int)x_floor, y0 = (int)y_floor;
    int x1 = wp_wrap_texel(x0 + 1, w, t->wrap), y1 = wp_wrap_texel(y0 + 1, h, t->wrap);
    x0 = wp_wrap_texel(x0, w, t->wrap);
    y0 = wp_wrap_texel(y0, h, t->wrap);
    float3 top =
        (1.0f - ax) * wp_bitmap_texel(texels, t, x0, y0) + ax * wp_bitmap_texel(texels, t, x1, y0);
    float3 bottom =
        (1.0f - ax) * wp_bitmap_texel(texels, t, x0, y1) + ax * wp_bitmap_texel(texels, t, x1, y1);
    return (1.0f - ay) * top + ay * bottom;
}

#endif /* WP_TEXTURES_BITMAP_H */
