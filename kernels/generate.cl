/* Stage 1, generate: one camera ray per pixel for the wave's sample index.
 *
 * Slot i holds pixel i. Each ray goes through a uniformly jittered point of its
 * pixel (a one-pixel box filter) and starts with throughput 1, radiance 0,
 * depth 0, and the specular flag set so that an emitter seen directly counts.
 */
#include "rng.h"

__kernel void generate(WpFrame frame,
                       __global float4* ray_origin, __global float4* ray_direction,
                       __global float4* throughput, __global float4* radiance,
                       __global wp_uint* path_pixel, __global wp_uint* path_depth,
                       __global wp_uint* path_flags, __global wp_uint* ray_queue) {
    wp_uint slot = get_global_id(0);
    wp_uint pixel_count = frame.width * frame.height;
    if (slot >= pixel_count)
        return;
    wp_uint pixel = slot;
    wp_uint x = pixel % frame.width;
    wp_uint y = pixel / frame.width;
    float jx = wp_random(frame.seed, pixel, frame.sample_index, 0u, WP_DIM_JITTER_X);
    float jy = wp_random(frame.seed, pixel, frame.sample_index, 0u, WP_DIM_JITTER_Y);
    /* Film coordinates in [-1, 1]: x to the right, y up (row 0 is the top). */
    float sx = 2.0f * ((float)x + jx) / (float)frame.width - 1.0f;
    float sy = 1.0f - 2.0f * ((float)y + jy) / (float)frame.height;
    float3 direction = normalize(frame.camera.forward.xyz + sx * frame.camera.right.xyz +
                                 sy * frame.camera.up.xyz);

    ray_origin[slot] = (float4)(frame.camera.eye.xyz, 0.0f);
    ray_direction[slot] = (float4)(direction, 0.0f);
    throughput[slot] = (float4)(1.0f, 1.0f, 1.0f, 0.0f);
    radiance[slot] = (float4)(0.0f);
    path_pixel[slot] = pixel;
    path_depth[slot] = 0u;
    path_flags[slot] = WP_PATH_SPECULAR;
    ray_queue[slot] = slot;
}
