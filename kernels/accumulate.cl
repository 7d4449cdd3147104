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
#include "stage.h"

/* Accumulate's work for one finished path: slot's radiance into its pixel. */
static inline void wp_accumulate_path(WP_STAGE_PARAMETERS, wp_uint slot) {
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

__kernel void accumulate(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= launch.count)
        return;
    wp_accumulate_path(WP_STAGE_ARGUMENTS, finished_queue[index]);
}
