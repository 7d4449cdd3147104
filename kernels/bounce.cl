/* Fused plan "bounce": intersect, shade and shadow of one queued ray in one
 * work-item (src/render/wavefront.cpp, LaunchPlan::Bounce).
 *
 * The same functions as the stage kernels, in the same order, so the image
 * is the stages plan's: the closest hit stays in registers instead of going
 * through hit_t/hit_primitive, and the shadow ray that shade makes is traced
 * at once instead of through the shadow queue. Survivors go to the other ray
 * queue and finished paths to the finished queue, as shade's do; the shadow
 * counter only counts the rays (for the statistics). */
#include "shade.cl"
#include "shadow.cl"
#include "stage.h"
#include "traverse.h"

__kernel void bounce(WP_FUSED_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= counters[launch.ray_queue])
        return;
    wp_uint slot = wp_ray_queue(ray_queues, frame, launch.ray_queue)[index];
    WP_SCENE_VIEW(scene);
    /* Drawn before the traversal, which hides their latency (shade.cl). */
    float4 first, second;
    wp_shade_numbers(frame, path_pixel, path_sample, path_depth, slot, &first, &second);
    float t;
    wp_uint primitive = wp_closest_hit(&scene, wp_load_xyz(ray_origin, slot),
                                       wp_load_xyz(ray_direction, slot), INFINITY, &t);
    WpShadowRay shadow;
    int outcome = wp_shade_path(WP_STAGE_ARGUMENTS, slot, primitive, t, first, second, &shadow);
    if (shadow.made) {
        atomic_inc(&counters[WP_COUNTER_SHADOW_RAYS]);
        wp_trace_shadow_ray(&scene, &shadow, radiance, slot);
    }
#if WP_MIRROR_NEE /* after the plain one, as the stages plan adds them */
    if (shadow.mirror_made) {
        atomic_add(&counters[WP_COUNTER_SHADOW_RAYS], 2u); /* two legs, as the stages count */
        wp_trace_mirror_shadow_ray(&scene, &shadow.mirror, radiance, slot);
    }
#endif
    wp_queue_shaded_path(ray_queues, finished_queue, counters, frame, launch, slot, outcome);
}
