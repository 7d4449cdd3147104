/* Stage 4, shadow: an any-hit test for each queued shadow ray; an unblocked
 * ray adds the contribution that shade computed for it to its path. */
#include "stage.h"
#include "traverse.h"

__kernel void shadow(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= launch.count)
        return;
    wp_uint slot = shadow_queue[index];
    WpSceneView scene = WP_SCENE_VIEW();
    /* Scalar loads and a per-component update keep vector instructions out
     * of the stage, so that it vectorises (traverse.h). The direction's w is
     * the segment's length. */
    if (!wp_occluded(&scene, wp_load_xyz(shadow_origin, slot), wp_load_xyz(shadow_direction, slot),
                     wp_load_w(shadow_direction, slot))) {
        __global float* sum = (__global float*)(radiance + slot);
        __global const float* add = (__global const float*)(shadow_contribution + slot);
        sum[0] += add[0];
        sum[1] += add[1];
        sum[2] += add[2];
        sum[3] += add[3];
    }
}

/* The same test for a shadow ray that a fused kernel traces as soon as shade
 * made it (bounce.cl, wave.cl): the same additions to the same radiance. */
static inline void wp_trace_shadow_ray(const WpSceneView* scene, const WpShadowRay* ray,
                                       __global float4* radiance, wp_uint slot) {
    if (!wp_occluded(scene, ray->origin, ray->direction, ray->length)) {
        __global float* sum = (__global float*)(radiance + slot);
        sum[0] += ray->contribution.x;
        sum[1] += ray->contribution.y;
        sum[2] += ray->contribution.z;
    }
}
