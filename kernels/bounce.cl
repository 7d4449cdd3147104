/* Fused plan "bounce": intersect, shade and shadow of one queued ray in one
 * work-item (src/render/wavefront.cpp, LaunchPlan::Bounce).
 *
 * The same functions as the stage kernels, in the same order
 * (wp_fused_bounce, fused_bounce.h), so the image is the stages plan's.
 * Survivors go to the other ray queue and finished paths to the finished
 * queue, as shade's do; the shadow counter only counts the rays (for the
 * statistics). */
#include "fused_bounce.h"
#include "stage.h"

__kernel void bounce(WP_FUSED_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= counters[launch.ray_queue])
        return;
    wp_uint slot = wp_ray_queue(ray_queues, frame, launch.ray_queue)[index];
    WP_SCENE_VIEW(scene);
    wp_uint shadows = 0u;
    int outcome = wp_fused_bounce(WP_STAGE_ARGUMENTS, &scene, slot, &shadows);
    if (shadows > 0u)
        atomic_add(&counters[WP_COUNTER_SHADOW_RAYS], shadows);
    wp_queue_shaded_path(ray_queues, finished_queue, counters, frame, launch, slot, outcome);
}
