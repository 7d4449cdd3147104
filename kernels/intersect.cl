/* Stage 2, intersect: the closest hit of every queued ray.
 *
 * The queue's length is read from the counters rather than passed in,
 * because generate appended to it after the host last looked; the host
 * launches enough work-items for the most it can hold. Rays are loaded as
 * scalars so that the stage vectorises (traverse.h). */
#include "stage.h"
#include "traverse.h"

__kernel void intersect(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    int queued = index < counters[launch.ray_queue];
    if (!WP_TRACE_SURPLUS_ITEMS && !queued)
        return;
    wp_uint slot = queued ? wp_ray_queue(ray_queues, frame, launch.ray_queue)[index] : 0u;
    WP_SCENE_VIEW(scene);
    float t;
    wp_uint hit = wp_closest_hit(&scene, wp_load_xyz(ray_origin, slot),
                                 wp_load_xyz(ray_direction, slot), INFINITY, &t);
    if (queued) {
        hit_primitive[slot] = hit;
        hit_t[slot] = t;
    }
}
