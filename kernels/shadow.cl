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
    float4 segment = shadow_direction[slot]; /* xyz unit direction, w length */
    if (!wp_occluded(&scene, shadow_origin[slot].xyz, segment.xyz, segment.w))
        radiance[slot] += shadow_contribution[slot];
}
