/* Fused kernel "tail": a wave's last, short iterations in one launch
 * (src/render/wavefront.cpp, trace_bounces). Once few paths of a wave are
 * left (no regeneration), each of the stages plan's iterations costs its
 * launches and a blocking counter read for a few hundred rays; here
 * work-item i takes ray queue entry i and traces that path on, bounce after
 * bounce, for at most launch.count bounces: the iterations left before the
 * host next folds the film (so a path ends in the same film batch as in the
 * stages plan), or WP_TAIL_BOUNCES.
 *
 * Each bounce is wp_fused_bounce (fused_bounce.h), as in bounce.cl: each
 * path's radiance is the stages plan's float for float. A path that goes on
 * after launch.count bounces is pushed onto the other ray queue, an ended
 * one onto the finished queue, for accumulate (launched after this, as after
 * shade: each slot is in it once, so the film adds as the stages plan does).
 *
 * Counts: tail_lengths[k - 1] the paths that traced k rays here (from which
 * the host has the rays of each bounce), counters[SHADOW_RAYS] the shadow
 * rays (counted only: no shadow queue), CAPPED as shade counts it. */
#include "fused_bounce.h"
#include "stage.h"

__kernel void tail(WP_FUSED_PARAMETERS) {
    wp_uint index = get_global_id(0);
    if (index >= counters[launch.ray_queue])
        return;
    wp_uint slot = wp_ray_queue(ray_queues, frame, launch.ray_queue)[index];
    WP_SCENE_VIEW(scene);
    wp_uint rays = 0u, shadows = 0u;
    int outcome = WP_SHADED_GOES_ON;
    while (outcome == WP_SHADED_GOES_ON && rays < launch.count) {
        outcome = wp_fused_bounce(WP_STAGE_ARGUMENTS, &scene, slot, &shadows);
        ++rays;
    }
    wp_queue_shaded_path(ray_queues, finished_queue, counters, frame, launch, slot, outcome);
    atomic_inc(&tail_lengths[rays - 1u]);
    if (shadows > 0u)
        atomic_add(&counters[WP_COUNTER_SHADOW_RAYS], shadows);
}
