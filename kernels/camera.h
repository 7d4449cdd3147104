/* The camera ray of a sample: where in its pixel it goes (the pixel filter)
 * and where it leaves the camera (the pinhole, or a point of a thin lens).
 * The camera's fields are described with WpCamera (wp_shared.h); generate.cl
 * calls these. */
#ifndef WP_CAMERA_H
#define WP_CAMERA_H

#include "wp_shared.h" /* first: FP_CONTRACT OFF */

#include "sampling.h"
#include "scene_features.h"

/* The filters are separable, f(x) f(y) as in Mitsuba's film, so each axis
 * draws its offset from the pixel's centre on its own from f's normalised
 * 1D density; the sample then counts with weight 1 and the film stays the
 * per-pixel mean of its samples, which converges to the filtered image
 * (sum of f L over sum of f) that Mitsuba's splatting film converges to.
 *
 * Each offset comes from one uniform number u by inverting the CDF of |x|
 * (filters are even): u's side of 1/2 is the sign, and v = |2u - 1| is
 * uniform in [0, 1] for the magnitude. */

#if WP_HAS_TENT_FILTER
/* The tent 1 - |x| / r on [-r, r]: |x| has CDF 1 - (1 - |x|/r)^2. */
static inline float wp_sample_tent(float u, float radius) {
    float v = fabs(2.0f * u - 1.0f);
    float magnitude = radius * (1.0f - sqrt(fmax(0.0f, 1.0f - v)));
    return u < 0.5f ? -magnitude : magnitude;
}
#endif

#if WP_HAS_GAUSSIAN_FILTER
/* Mitsuba's windowed Gaussian, exp(-(k x)^2) - bias on [-r, r] with
 * k = 1 / (stddev sqrt 2) and bias its value at r, so it falls to 0 there.
 * |x| has the unnormalised CDF G(y) = sqrt(pi) / (2 k) erf(k y) - bias y,
 * which no closed form inverts: G(y) = v G(r) is solved by bisection, 24
 * halvings of [0, r], as fine as float resolves r. A fixed count: no branch
 * that depends on the data leaves the loop. */
#define WP_GAUSSIAN_FILTER_STEPS 24
static inline float wp_gaussian_filter_cdf(float y, float scale, float bias) {
    return (0.886226925452758f / scale) * erf(scale * y) - bias * y; /* sqrt(pi) / 2 */
}
static inline float wp_sample_gaussian_filter(float u, float radius, float scale, float bias) {
    float v = fabs(2.0f * u - 1.0f);
    float target = v * wp_gaussian_filter_cdf(radius, scale, bias);
    float lo = 0.0f, hi = radius;
    for (int i = 0; i < WP_GAUSSIAN_FILTER_STEPS; ++i) {
        float mid = 0.5f * (lo + hi);
        if (wp_gaussian_filter_cdf(mid, scale, bias) < target)
            lo = mid;
        else
            hi = mid;
    }
    float magnitude = 0.5f * (lo + hi);
    return u < 0.5f ? -magnitude : magnitude;
}
#endif

#if WP_HAS_TENT_FILTER || WP_HAS_GAUSSIAN_FILTER
/* The filter's CDF over signed offsets, F(x) = 1/2 + sign(x) C(|x|) / 2 with
 * C the normalised CDF of |x| above: the function the two samplers invert. */
static inline float wp_filter_cdf(const WpCamera* camera, float x) {
    float y = fmin(fabs(x), camera->filter_radius), c = 1.0f;
#if WP_HAS_TENT_FILTER
    if (camera->filter == WP_FILTER_TENT) {
        float t = 1.0f - y / camera->filter_radius;
        c = 1.0f - t * t;
    }
#endif
#if WP_HAS_GAUSSIAN_FILTER
    if (camera->filter == WP_FILTER_GAUSSIAN)
        c = wp_gaussian_filter_cdf(y, camera->filter_scale, camera->filter_bias) /
            wp_gaussian_filter_cdf(camera->filter_radius, camera->filter_scale,
                                   camera->filter_bias);
#endif
    return x < 0.0f ? 0.5f - 0.5f * c : 0.5f + 0.5f * c;
}

/* Mitsuba's film samples only inside the image (hdrfilm's sample_border is
 * off by default) and splats each sample with the filter's weight, so a
 * pixel within the filter's radius of the edge converges to the weighted
 * mean over the part of its footprint inside the image. The same
 * expectation here: u is mapped into [F(lo), F(hi)], the CDF's values at the
 * offsets where the image ends, so the offset follows the filter restricted
 * to the image. Drawn from the whole filter instead, the Cornell box's
 * outermost ring of pixels at 32x32 came out 18 % darker than Mitsuba's
 * (docs/lights-and-camera.md). Interior pixels keep u as it is. */
static inline float wp_filter_inside_image(const WpCamera* camera, float centre, wp_uint size,
                                           float u) {
    float r = camera->filter_radius;
    float lo = fmax(-r, -centre), hi = fmin(r, (float)size - centre);
    if (lo > -r || hi < r) {
        float f_lo = wp_filter_cdf(camera, lo), f_hi = wp_filter_cdf(camera, hi);
        u = f_lo + u * (f_hi - f_lo);
    }
    return u;
}
#endif

/* A sample's position within the image, in pixels from the image's left
 * (top) edge, for pixel column (row) `index` of `size` and the uniform
 * number u. The box keeps the form it always had, index + u, so its images
 * do not change by a bit. */
static inline float wp_filter_position(const WpCamera* camera, wp_uint index, wp_uint size,
                                       float u) {
    float centre = (float)index + 0.5f;
#if WP_HAS_TENT_FILTER
    if (camera->filter == WP_FILTER_TENT)
        return centre + wp_sample_tent(wp_filter_inside_image(camera, centre, size, u),
                                       camera->filter_radius);
#endif
#if WP_HAS_GAUSSIAN_FILTER
    if (camera->filter == WP_FILTER_GAUSSIAN)
        return centre + wp_sample_gaussian_filter(wp_filter_inside_image(camera, centre, size, u),
                                                  camera->filter_radius, camera->filter_scale,
                                                  camera->filter_bias);
#endif
    return (float)index + u;
}

#if WP_HAS_LENS
/* A thin lens (Mitsuba's thinlens): the pinhole ray's direction d (not
 * normalised; its component along forward is 1) meets the plane of focus, at
 * distance focus along forward, in eye + focus d. The ray leaves the aperture
 * point eye + a instead, a uniform on the disk of the aperture radius in the
 * plane of right and up, and passes through that point: everything on the
 * plane of focus is sharp, and a point at distance z spreads over a disk of
 * radius radius |1/z - 1/focus| at unit distance. (u1, u2) picks a. */
static inline void wp_thin_lens(const WpCamera* camera, float u1, float u2, float3* origin,
                                float3* direction) {
    float2 disk = wp_sample_concentric_disk(u1, u2);
    float3 offset = disk.x * camera->lens_right.xyz + disk.y * camera->lens_up.xyz;
    *origin = *origin + offset;
    *direction = camera->lens_right.w * *direction - offset;
}
#endif

#endif /* WP_CAMERA_H */
