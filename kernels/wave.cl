/* Fused plan "wave": one kernel per wave, a megakernel (src/render/
 * wavefront.cpp, LaunchPlan::Wave). Work-item i runs slot i's paths whole:
 * generate, then intersect, shade and shadow bounce after bounce until the
 * path ends, then accumulate; and that for up to launch.count of the slot's
 * tasks. No queue, no host synchronisation between bounces.
 *
 * The same functions as the stage kernels in the same order (each bounce is
 * wp_fused_bounce, fused_bounce.h): a slot's samples are the stages plan's,
 * added to the film in the same order.
 *
 * Counters (read by the host after the launch): QUEUE_A the rays traced,
 * QUEUE_B the samples started (camera rays), SHADOW_RAYS the shadow rays;
 * each work-item adds its totals once, not one atomic per ray. */
#include "accumulate.cl"
#include "fused_bounce.h"
#include "generate.cl"
#include "stage.h"

__kernel void wave(WP_FUSED_PARAMETERS) {
    wp_uint slot = get_global_id(0);
    if (slot >= frame.pool_size)
        return;
    WP_SCENE_VIEW(scene);
    wp_uint rays = 0, samples = 0, shadows = 0;
    for (; samples < launch.count; ++samples) {
        if (!wp_generate_path(WP_STAGE_ARGUMENTS, slot))
            break;
        int goes_on = 1;
        while (goes_on) {
            int outcome = wp_fused_bounce(WP_STAGE_ARGUMENTS, &scene, slot, &shadows);
            ++rays;
            if (outcome == WP_SHADED_CAPPED)
                atomic_inc(&counters[WP_COUNTER_CAPPED]);
            goes_on = outcome == WP_SHADED_GOES_ON;
        }
        wp_accumulate_path(WP_STAGE_ARGUMENTS, slot);
    }
    if (rays > 0) {
        atomic_add(&counters[WP_COUNTER_QUEUE_A], rays);
        atomic_add(&counters[WP_COUNTER_QUEUE_B], samples);
        atomic_add(&counters[WP_COUNTER_SHADOW_RAYS], shadows);
    }
}
