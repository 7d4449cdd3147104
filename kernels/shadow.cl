/* Stage 4, shadow: an any-hit test for each queued shadow ray; an unblocked
 * ray adds the contribution that shade computed for it to its path. */
#include "traverse.h"

__kernel void shadow(WpFrame frame, wp_uint shadow_count, __global const wp_uint* shadow_queue,
                     __global const float4* shadow_origin, __global const float4* shadow_direction,
                     __global const float4* shadow_contribution,
                     __global const WpTriangle* triangles, __global const WpSphere* spheres,
                     __global float4* radiance) {
    wp_uint index = get_global_id(0);
    if (index >= shadow_count)
        return;
    wp_uint slot = shadow_queue[index];
    float4 segment = shadow_direction[slot]; /* xyz unit direction, w length */
    if (!wp_occluded(shadow_origin[slot].xyz, segment.xyz, segment.w, triangles, spheres, frame))
        radiance[slot] += shadow_contribution[slot];
}
