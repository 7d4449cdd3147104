/* Stage 5, accumulate: adds each finished path's radiance to the film.
 *
 * A wave holds exactly one sample per pixel, so every work-item owns its
 * pixel and no float atomics are needed. The film keeps the sum and the sum of
 * squares (for the per-pixel variance) and the sum over odd sample indices
 * (the even half-film is the difference), from which the error of an image
 * can be estimated without a reference.
 *
 * A non-finite sample would poison its pixel forever: it is dropped (counts
 * as zero) and counted, and the count is reported after every render.
 */
#include "wp_shared.h"

__kernel void accumulate(WpFrame frame, __global const float4* radiance,
                         __global const wp_uint* path_pixel, __global float4* film_sum,
                         __global float4* film_sum_squares, __global float4* film_odd_sum,
                         __global wp_uint* counters) {
    wp_uint slot = get_global_id(0);
    if (slot >= frame.width * frame.height)
        return;
    float4 value = (float4)(radiance[slot].xyz, 0.0f);
    if (!(isfinite(value.x) && isfinite(value.y) && isfinite(value.z))) {
        atomic_inc(&counters[WP_COUNTER_NONFINITE]);
        value = (float4)(0.0f);
    }
    wp_uint pixel = path_pixel[slot];
    film_sum[pixel] += value;
    film_sum_squares[pixel] += value * value;
    if (frame.sample_index & 1u)
        film_odd_sum[pixel] += value;
}
