/* The shadow queue put in order of the rays' origins before the shadow stage
 * traces it through the hierarchy (WP_USE_BVH, the stages plan): consecutive
 * work-items then start in the same part of the scene and walk the same
 * nodes and leaves while those are still in the caches. At 10^6 triangles
 * the hierarchy is far larger than the caches and the any-hit traversal
 * waits mostly on loads that miss them (docs/performance.md, "Any-hit
 * traversal", third attempt, has the measurements).
 *
 * The key is a Morton code of the origin's cell in the scene's box (the root
 * node's children's boxes), WP_SHADOW_ORDER_AXIS_BITS bits an axis; a
 * counting sort in three launches over the queue:
 *   shadow_order_count    each ray's key (shadow_key, by queue place) and
 *                         the count of each key (shadow_key_counts[k]);
 *   shadow_order_scan     one work-item: the counts become the prefix sums,
 *                         where each key's range starts;
 *   shadow_order_scatter  each slot written at its key's cursor in
 *                         shadow_order, and its ray's origin and direction
 *                         at the same place of shadow_order_origin and
 *                         _direction.
 * The host zeroes shadow_key_counts before the first; shadow then takes its
 * slots from shadow_order and its rays from the sorted copies, read in
 * order (WpLaunch.sorted). The copies matter: read through the sorted slots,
 * the rays' own buffers are gathered from all over, and at 10^6 triangles
 * those cache misses cost more than the order saves (docs/performance.md). Within a key the order
 * is whichever work-item came first. No answer depends on the order: each queued slot is traced
 * once and adds to its own radiance, so the image is the same bit for bit. */
#ifndef WP_SHADOW_ORDER_H
#define WP_SHADOW_ORDER_H

#include "stage.h"
#include "traverse.h" /* wp_load_xyz */

#if WP_USE_BVH

/* v's low 10 bits spread to every third bit (bit i to bit 3 i). */
static inline wp_uint wp_spread_bits3(wp_uint v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

/* The cell of coordinate x along an axis from low to high, of `cells`:
 * clamped, so that an origin just outside the box (an offset ray) or a
 * flat box gives a cell all the same. */
static inline wp_uint wp_axis_cell(float x, float low, float high, wp_uint cells) {
    float at = (x - low) / (high - low) * (float)cells;
    return at > 0.0f ? min((wp_uint)at, cells - 1u) : 0u; /* NaN (a flat box): 0 */
}

/* The key of a ray from `origin`: the Morton code of its cell in the box of
 * the root's children. */
static inline wp_uint wp_shadow_order_key(__global const WpBvhNode* root, float3 origin) {
    float3 low = (float3)(INFINITY), high = (float3)(-INFINITY);
    for (int i = 0; i < 4; ++i) {
        if (root->count[i] == WP_BVH_EMPTY)
            continue;
        low = fmin(low, (float3)(root->lower_x[i], root->lower_y[i], root->lower_z[i]));
        high = fmax(high, (float3)(root->upper_x[i], root->upper_y[i], root->upper_z[i]));
    }
    const wp_uint cells = 1u << WP_SHADOW_ORDER_AXIS_BITS;
    return wp_spread_bits3(wp_axis_cell(origin.x, low.x, high.x, cells)) |
           wp_spread_bits3(wp_axis_cell(origin.y, low.y, high.y, cells)) << 1 |
           wp_spread_bits3(wp_axis_cell(origin.z, low.z, high.z, cells)) << 2;
}

__kernel void shadow_order_count(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= launch.count)
        return;
    wp_uint slot = shadow_queue[index];
    wp_uint key = wp_shadow_order_key(bvh_nodes, wp_load_xyz(shadow_origin, slot));
    shadow_key[index] = key;
    atomic_inc(&shadow_key_counts[key]);
}

__kernel void shadow_order_scan(WP_STAGE_PARAMETERS) {
    if (get_global_id(0) != 0u)
        return;
    wp_uint start = 0u;
    for (wp_uint k = 0u; k < WP_SHADOW_KEY_COUNT; ++k) {
        wp_uint count = shadow_key_counts[k];
        shadow_key_counts[k] = start;
        start += count;
    }
}

__kernel void shadow_order_scatter(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= launch.count)
        return;
    wp_uint slot = shadow_queue[index];
    wp_uint place = atomic_inc(&shadow_key_counts[shadow_key[index]]);
    shadow_order[place] = slot;
    shadow_order_origin[place] = shadow_origin[slot];
    shadow_order_direction[place] = shadow_direction[slot];
}

#endif /* WP_USE_BVH */

#endif /* WP_SHADOW_ORDER_H */
