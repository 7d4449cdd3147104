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
    wp_uint mirror_sphere_count;
    wp_uint emitter_count;
    float emitter_pick; /* the probability of choosing an emitter, not a triangle (lights.h) */
    wp_uint instance_count;
} WpSceneView;

#define WP_SCENE_ASSIGN(name, type) view->name = name;
/* Written through a pointer, not returned: a returned struct is an sret
 * argument, which Oclgrind 21.10 cannot run once inlined (bsdf/interface.h). */
static inline void wp_scene_view(WpSceneView* view,
                                 WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER)) {
    WP_SCENE_BUFFERS(WP_SCENE_ASSIGN)
    view->triangle_count = frame.triangle_count;
    view->sphere_count = frame.sphere_count;
    view->light_count = frame.light_count;
    view->light_area = frame.light_area;
    view->mirror_group_count = frame.mirror_group_count;
    view->mirror_sphere_count = frame.mirror_sphere_count;
    view->emitter_count = frame.emitter_count;
    view->emitter_pick = frame.emitter_pick;
    view->instance_count = frame.instance_count;
}

/* The stages' per-item work lives in functions that take the stage's own
 * parameters (WP_STAGE_PARAMETERS) and are called with WP_STAGE_ARGUMENTS, so
 * that a fused kernel (bounce.cl, wave.cl) runs the very same code. */
#define WP_PATH_ARGUMENT(name, type, per_slot, per_pixel, fixed) , name
#define WP_STAGE_ARGUMENTS                                                                         \
    frame, launch WP_SCENE_BUFFERS(WP_SCENE_ARGUMENT) WP_PATH_BUFFERS(WP_PATH_ARGUMENT)

/* The fused kernels' parameters: the same, but every buffer `restrict` (they
 * are distinct buffers; read-only ones may share a dummy). Without it the
 * compiler must assume that a store to the path state may change the scene,
 * and reloads (and recomputes from) the scene's primitives for every
 * work-item instead of once per work-group loop. */
#define WP_SCENE_PARAMETER_RESTRICT(name, type) , __global const type* restrict name
#define WP_PATH_PARAMETER_RESTRICT(name, type, per_slot, per_pixel, fixed)                         \
    , __global type* restrict name
#define WP_FUSED_PARAMETERS                                                                        \
    WpFrame frame, WpLaunch launch WP_SCENE_BUFFERS(WP_SCENE_PARAMETER_RESTRICT)                   \
                       WP_PATH_BUFFERS(WP_PATH_PARAMETER_RESTRICT)

/* A two-segment shadow ray through a planar mirror (mirror_light.h) and what
 * it adds if both legs are unblocked. */
typedef struct {
    float4 origin, direction;   /* leg 1, x to the mirror (direction w: length) */
    float4 origin2, direction2; /* leg 2, the mirror to the light */
    float4 contribution;
} WpMirrorShadow;

/* The shadow rays that shade made: the stages plan queues them for the
 * shadow stage (the two-leg one for its mirror queue), the fused plans trace
 * them at once (shadow.cl, wp_trace_shadow_ray, wp_trace_mirror_shadow_ray).
 * Without WP_MIRROR_NEE the mirror members are never set nor read, and the
 * compiler drops them. */
typedef struct {
    float3 origin;
    float3 direction;
    float length;
    float3 contribution; /* added to the path's radiance if unblocked */
    int made;
    WpMirrorShadow mirror;
    int mirror_made;
} WpShadowRay;

/* Inside a stage: declares `name`, the scene view of this launch. */
#define WP_SCENE_ARGUMENT(name, type) , name
#define WP_SCENE_VIEW(name)                                                                        \
    WpSceneView name;                                                                              \
    wp_scene_view(&name, frame WP_SCENE_BUFFERS(WP_SCENE_ARGUMENT))

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

/* Appends `slot` to the queue whose length is counters[counter] where
 * `push` is set, for a whole work-group at once: work-item 0 numbers the
 * group's pushes and reserves their range with one atomic_add, then every
 * pushing work-item writes its slot at its place. One atomic per item, on a
 * counter every core adds to, cost more than the work it queued where that
 * work is small: in generate the lock xadd held 74 % of the kernel's samples
 * (perf annotate, the hexroom on two PoCL threads). Every work-item of the
 * group must call it, pushing or not, since it has barriers; `place` holds
 * WP_MAX_WORK_GROUP_SIZE entries of local memory (OpenCL C 1.2 declares
 * local arrays in the kernel only). */
static inline void wp_group_queue_push(__global wp_uint* queue, __global wp_uint* counters,
                                       wp_uint counter, int push, wp_uint slot,
                                       __local wp_uint* place, __local wp_uint* first_place) {
    wp_uint item = get_local_id(0);
    place[item] = push ? 1u : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (item == 0u) {
        wp_uint pushed = 0u;
        for (wp_uint i = 0u; i < get_local_size(0); ++i) {
            wp_uint pushes = place[i];
            place[i] = pushed;
            pushed += pushes;
        }
        *first_place = pushed ? atomic_add(&counters[counter], pushed) : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (push)
        queue[*first_place + place[item]] = slot;
}

#endif /* WP_STAGE_H */
