/* Fused plan "wave": one kernel per wave, a megakernel (src/render/
 * wavefront.cpp, LaunchPlan::Wave). Work-item i runs slot i's paths whole:
 * generate, then intersect, shade and shadow bounce after bounce until the
 * path ends, then accumulate; and that for up to launch.count of the slot's
 * tasks. No queue, no host synchronisation between bounces.
 *
 * The same functions as the stage kernels in the same order: a slot's
 * samples are the stages plan's, added to the film in the same order.
 *
 * Counters (read by the host after the launch): QUEUE_A the rays traced,
 * QUEUE_B the samples started (camera rays), SHADOW_RAYS the shadow rays;
 * each work-item adds its totals once, not one atomic per ray. */
#include "accumulate.cl"
#include "generate.cl"
#include "shade.cl"
#include "shadow.cl"
#include "stage.h"
#include "traverse.h"

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
            /* Drawn before the traversal, which hides their latency (shade.cl). */
            float4 first, second;
            wp_shade_numbers(frame, path_pixel, path_sample, path_depth, slot, &first, &second);
            float t;
            wp_uint primitive = wp_closest_hit(&scene, wp_load_xyz(ray_origin, slot),
                                               wp_load_xyz(ray_direction, slot), INFINITY, &t);
            ++rays;
            WpShadowRay shadow;
            int outcome =
                wp_shade_path(WP_STAGE_ARGUMENTS, slot, primitive, t, first, second, &shadow);
            if (outcome == WP_SHADED_CAPPED)
                atomic_inc(&counters[WP_COUNTER_CAPPED]);
            goes_on = outcome == WP_SHADED_GOES_ON;
            if (shadow.made) {
                ++shadows;
                wp_trace_shadow_ray(&scene, &shadow, radiance, slot);
            }
#if WP_MIRROR_NEE /* after the plain one, as the stages plan adds them */
            if (shadow.mirror_made) {
                shadows += 2u; /* two legs, as the stages plan counts them */
                wp_trace_mirror_shadow_ray(&scene, &shadow.mirror, radiance, slot);
            }
#endif
        }
        wp_accumulate_path(WP_STAGE_ARGUMENTS, slot);
    }
    if (rays > 0) {
        atomic_add(&counters[WP_COUNTER_QUEUE_A], rays);
        atomic_add(&counters[WP_COUNTER_QUEUE_B], samples);
        atomic_add(&counters[WP_COUNTER_SHADOW_RAYS], shadows);
    }
}
