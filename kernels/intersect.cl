/* Stage 2, intersect: the closest hit of every queued ray.
 *
 * The queue's length is read from counters[ray_counter] rather than passed
 * in, because generate appended to it after the host last looked; the host
 * launches enough work-items for the most it can hold. */
#include "traverse.h"

__kernel void intersect(WpFrame frame, __global const wp_uint* ray_queue,
                        __global const wp_uint* counters, wp_uint ray_counter,
                        __global const float4* ray_origin, __global const float4* ray_direction,
                        __global const WpTriangle* triangles, __global const WpSphere* spheres,
                        __global float* hit_t, __global wp_uint* hit_primitive) {
    wp_uint index = get_global_id(0);
    if (index >= counters[ray_counter])
        return;
    wp_uint slot = ray_queue[index];
    float t;
    hit_primitive[slot] = wp_closest_hit(ray_origin[slot].xyz, ray_direction[slot].xyz, INFINITY,
                                         triangles, spheres, frame, &t);
    hit_t[slot] = t;
}
