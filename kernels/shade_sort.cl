/* Shade sorted by material (--shade-order sorted): between intersect and
 * shade, the ray queue is put in order of what each ray hit, the kind of its
 * material (WpMaterial.kind), or WP_SHADE_KEY_MISS for a ray that left the
 * scene, so that shade's work-groups (a CPU's SIMD lanes, a GPU's warps) meet
 * one BSDF at a time instead of every kind the queue happens to mix.
 *
 * A counting sort in two launches over the queue, each work-group doing its
 * bookkeeping in local memory and one global atomic per key, as shade
 * compacts its pushes (shade.cl):
 *   shade_sort_count  counts the rays of each key: shade_key_counts[k];
 *   shade_sort        takes the prefix sums over the keys (where each key's
 *                     range starts), reserves each group's places within its
 *                     keys' ranges (shade_key_counts[WP_SHADE_KEY_COUNT + k],
 *                     the cursors) and writes every slot at its place in
 *                     shade_order.
 * The host zeroes shade_key_counts before the first. Shade then takes its
 * slots from shade_order (WpLaunch.sorted). Within a key the order depends on
 * which group reserved first; nothing computed does, as every slot owns its
 * own pixels and random numbers, so the image is the same bit for bit.
 */
#include "primitive.h"
#include "stage.h"

/* The key of a ray that hit `primitive` (WP_NO_HIT: none). */
static inline wp_uint wp_shade_key(const WpSceneView* scene, wp_uint primitive) {
    if (primitive == WP_NO_HIT)
        return WP_SHADE_KEY_MISS;
    return scene->materials[wp_primitive_material(scene, primitive)].kind;
}

/* This work-item's entry of the launch's ray queue: its slot and its key. A
 * surplus work-item past the queue's end has no key (WP_SHADE_KEY_COUNT,
 * counted nowhere) and slot 0, which it never writes. */
static inline wp_uint wp_queued_shade_key(const WpSceneView* scene, WpFrame frame, WpLaunch launch,
                                          __global wp_uint* counters, __global wp_uint* ray_queues,
                                          __global wp_uint* hit_primitive, wp_uint* slot) {
    wp_uint index = get_global_id(0);
    if (index >= counters[launch.ray_queue]) {
        *slot = 0u;
        return WP_SHADE_KEY_COUNT;
    }
    *slot = wp_ray_queue(ray_queues, frame, launch.ray_queue)[index];
    return wp_shade_key(scene, hit_primitive[*slot]);
}

__kernel void shade_sort_count(WP_STAGE_PARAMETERS) {
    __local wp_uint keys[WP_MAX_WORK_GROUP_SIZE];
    WP_SCENE_VIEW(scene);
    wp_uint item = get_local_id(0), slot;
    keys[item] =
        wp_queued_shade_key(&scene, frame, launch, counters, ray_queues, hit_primitive, &slot);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (item == 0u) {
        wp_uint in_group[WP_SHADE_KEY_COUNT];
        for (wp_uint k = 0u; k < WP_SHADE_KEY_COUNT; ++k)
            in_group[k] = 0u;
        for (wp_uint i = 0u; i < get_local_size(0); ++i)
            if (keys[i] < WP_SHADE_KEY_COUNT)
                ++in_group[keys[i]];
        for (wp_uint k = 0u; k < WP_SHADE_KEY_COUNT; ++k)
            if (in_group[k])
                atomic_add(&shade_key_counts[k], in_group[k]);
    }
}

__kernel void shade_sort(WP_STAGE_PARAMETERS) {
    __local wp_uint keys[WP_MAX_WORK_GROUP_SIZE];
    __local wp_uint place_in_group[WP_MAX_WORK_GROUP_SIZE]; /* among the group's rays of its key */
    __local wp_uint first_place[WP_SHADE_KEY_COUNT];        /* the group's first place per key */
    WP_SCENE_VIEW(scene);
    wp_uint item = get_local_id(0), slot;
    wp_uint key =
        wp_queued_shade_key(&scene, frame, launch, counters, ray_queues, hit_primitive, &slot);
    keys[item] = key;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (item == 0u) {
        wp_uint in_group[WP_SHADE_KEY_COUNT];
        for (wp_uint k = 0u; k < WP_SHADE_KEY_COUNT; ++k)
            in_group[k] = 0u;
        for (wp_uint i = 0u; i < get_local_size(0); ++i)
            if (keys[i] < WP_SHADE_KEY_COUNT)
                place_in_group[i] = in_group[keys[i]]++;
        wp_uint key_start = 0u; /* the prefix sum of the counts: where key k's range starts */
        for (wp_uint k = 0u; k < WP_SHADE_KEY_COUNT; ++k) {
            if (in_group[k])
                first_place[k] =
                    key_start + atomic_add(&shade_key_counts[WP_SHADE_KEY_COUNT + k], in_group[k]);
            key_start += shade_key_counts[k];
        }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (key < WP_SHADE_KEY_COUNT) {
        wp_uint place = first_place[key] + place_in_group[item];
        shade_order[place] = slot;
    }
}
