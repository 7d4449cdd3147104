/* Stage 5, accumulate: adds each finished path's radiance to the film.
 *
 * A pixel belongs to exactly one path slot (see WpFrame), and a slot appears
 * at most once in the finished queue, so every work-item owns its pixel and
 * no float atomics are needed. The film keeps, per pixel, the sum (w: the
 * sample count), the sum of squares (for the variance) and the sum over odd
 * sample indices (w: their count); the even half-film is the difference.
 *
 * A non-finite sample would poison its pixel forever: it is dropped (counts
 * as zero) and counted, and the count is reported after every render.
 */
#include "wp_shared.h"

__kernel void accumulate(WpFrame frame, __global const wp_uint* finished,
                         wp_uint finished_count, __global const float4* radiance,
                         __global const wp_uint* path_pixel, __global const wp_uint* path_sample,
                         __global float4* film_sum, __global float4* film_sum_squares,
                         __global float4* film_odd_sum, __global wp_uint* counters) {
    wp_uint index = get_global_id(0);
    if (index >= finished_count)
        return;
    wp_uint slot = finished[index];
    float4 value = (float4)(radiance[slot].xyz, 0.0f);
    if (!(isfinite(value.x) && isfinite(value.y) && isfinite(value.z))) {
        atomic_inc(&counters[WP_COUNTER_NONFINITE]);
        value = (float4)(0.0f);
    }
    wp_uint pixel = path_pixel[slot];
    film_sum[pixel] += (float4)(value.xyz, 1.0f);
    film_sum_squares[pixel] += value * value;
    if (path_sample[slot] & 1u)
        film_odd_sum[pixel] += (float4)(value.xyz, 1.0f);
}
