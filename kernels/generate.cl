/* Stage 1, generate: a camera ray for each slot given to it.
 *
 * A slot works through its own list of tasks (see WpFrame): task t of slot i
 * is pixel i + (t mod m) * pool_size, sample first_sample + t / m, where m is
 * the number of pixels the slot owns. Sample-major order means every pixel
 * gets its first sample before any pixel gets its second. A slot whose tasks
 * are done is not queued again.
 *
 * The host hands in every slot at the start of a wave, and, with
 * regeneration, the slots whose paths just finished (launch.from_finished),
 * so the ray queue stays full while long paths drain.
 *
 * Each ray goes through a point of its pixel drawn from the pixel filter (a
 * uniform one for the one-pixel box), from the eye or, with a thin lens, from
 * a point of the aperture (camera.h), and starts with throughput 1, radiance
 * 0, depth 0, and the specular flag set so that an emitter seen directly
 * counts.
 */
#include "camera.h"
#include "rng.h"
#include "stage.h"

/* Generate's work for one slot: starts its next task's camera ray and says
 * whether there was one (0: the slot has done all its tasks). */
static inline int wp_generate_path(WP_STAGE_PARAMETERS, wp_uint slot) {
    wp_uint pixel_count = frame.width * frame.height;
    wp_uint owned = (pixel_count - slot + frame.pool_size - 1u) / frame.pool_size;
    wp_uint task = path_task[slot];
    if (task >= owned * frame.sample_count)
        return 0;
    path_task[slot] = task + 1u;
    wp_uint pixel = slot + (task % owned) * frame.pool_size;
    wp_uint sample = frame.first_sample + task / owned;

    wp_uint x = pixel % frame.width;
    wp_uint y = pixel / frame.width;
    float jx = wp_random(frame.seed, pixel, sample, 0u, WP_DIM_JITTER_X);
    float jy = wp_random(frame.seed, pixel, sample, 0u, WP_DIM_JITTER_Y);
    /* Film coordinates in [-1, 1]: x to the right, y up (row 0 is the top). */
    float sx =
        2.0f * wp_filter_position(&frame.camera, x, frame.width, jx) / (float)frame.width - 1.0f;
    float sy =
        1.0f - 2.0f * wp_filter_position(&frame.camera, y, frame.height, jy) / (float)frame.height;
    float3 origin = frame.camera.eye.xyz;
    float3 direction =
        frame.camera.forward.xyz + sx * frame.camera.right.xyz + sy * frame.camera.up.xyz;
#if WP_HAS_LENS
    if (frame.camera.lens_up.w > 0.0f)
        wp_thin_lens(&frame.camera,
                     wp_random(frame.seed, pixel, sample, WP_LENS_BOUNCE, WP_DIM_LENS_U),
                     wp_random(frame.seed, pixel, sample, WP_LENS_BOUNCE, WP_DIM_LENS_V), &origin,
                     &direction);
#endif

    ray_origin[slot] = (float4)(origin, 0.0f);
    ray_direction[slot] = (float4)(normalize(direction), 0.0f);
    /* w: the eta^2 the path has crossed (estimator.h, WP_ROULETTE_RULE), none yet */
    throughput[slot] = (float4)(1.0f, 1.0f, 1.0f, 1.0f);
    radiance[slot] = (float4)(0.0f);
    path_pixel[slot] = pixel;
    path_sample[slot] = sample;
    path_depth[slot] = 0u;
    path_flags[slot] = WP_PATH_SPECULAR;
    return 1;
}

/* Generate kernel: one work-item per slot given to it. Its queue pushes are
 * compacted per work-group (stage.h, wp_group_queue_push), so surplus
 * work-items past the launch's count push nothing but still reach the
 * barriers. */
__kernel void generate(WP_STAGE_PARAMETERS) {
    __local wp_uint place[WP_MAX_WORK_GROUP_SIZE];
    __local wp_uint first_place;
    wp_uint index = get_global_id(0);
    wp_uint slot = 0u;
    int started = 0;
    if (index < launch.count) {
        slot = launch.from_finished ? finished_queue[index] : index;
        started = wp_generate_path(WP_STAGE_ARGUMENTS, slot);
    }
    wp_group_queue_push(wp_ray_queue(ray_queues, frame, launch.ray_queue), counters,
                        launch.ray_queue, started, slot, place, &first_place);
}
