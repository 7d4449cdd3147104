/* What every stage kernel has in common: its parameters, the scene as one
 * value, and the queues.
 *
 * Every stage is declared as
 *     __kernel void NAME(WP_STAGE_PARAMETERS)
 * that is (WpFrame frame, WpLaunch launch, then every buffer of
 * WP_SCENE_BUFFERS and WP_PATH_BUFFERS in list order, each under its own
 * name), and the host binds them all by the same lists
 * (src/render/device_buffers.cpp). A stage simply uses the buffers it needs;
 * the rest are unused pointers.
 */
#ifndef WP_STAGE_H
#define WP_STAGE_H

#include "wp_shared.h"

#define WP_SCENE_PARAMETER(name, type) , __global const type* name
#define WP_PATH_PARAMETER(name, type, per_slot, per_pixel, fixed) , __global type* name
#define WP_STAGE_PARAMETERS                                                                        \
    WpFrame frame,                                                                                 \
        WpLaunch launch WP_SCENE_BUFFERS(WP_SCENE_PARAMETER) WP_PATH_BUFFERS(WP_PATH_PARAMETER)

/* The scene as the traversal, surface and light code see it: its buffers and
 * its counts, in one value that functions take by pointer, so that a new
 * scene buffer (a hierarchy, a texture) reaches them without a new parameter
 * anywhere. */
#define WP_SCENE_MEMBER(name, type) __global const type* name;
typedef struct {
    WP_SCENE_BUFFERS(WP_SCENE_MEMBER)
    wp_uint triangle_count;
    wp_uint sphere_count;
    wp_uint light_count;
    float light_area; /* total emissive area: 1 / pdf of uniform area sampling */
    wp_uint mirror_group_count;
} WpSceneView;

#define WP_SCENE_ASSIGN(name, type) view.name = name;
static inline WpSceneView wp_scene_view(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER)) {
    WpSceneView view;
    WP_SCENE_BUFFERS(WP_SCENE_ASSIGN)
    view.triangle_count = frame.triangle_count;
    view.sphere_count = frame.sphere_count;
    view.light_count = frame.light_count;
    view.light_area = frame.light_area;
    view.mirror_group_count = frame.mirror_group_count;
    return view;
}

/* Inside a stage: the scene view of this launch. */
#define WP_SCENE_ARGUMENT(name, type) , name
#define WP_SCENE_VIEW() wp_scene_view(frame WP_SCENE_BUFFERS(WP_SCENE_ARGUMENT))

/* Ray queue `queue` (0 or 1) inside the ray_queues buffer. */
static inline __global wp_uint* wp_ray_queue(__global wp_uint* ray_queues, WpFrame frame,
                                             wp_uint queue) {
    return ray_queues + queue * frame.pool_size;
}

/* Appends `slot` to the queue whose length is counters[counter]. The order
 * of a queue depends on scheduling; nothing computed from it does, because
 * every slot owns its own pixels. */
static inline void wp_queue_push(__global wp_uint* queue, __global wp_uint* counters,
                                 wp_uint counter, wp_uint slot) {
    queue[atomic_inc(&counters[counter])] = slot;
}

#endif /* WP_STAGE_H */
