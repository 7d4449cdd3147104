/* Stage 4, shadow: an any-hit test for each queued shadow ray; an unblocked
 * ray adds the contribution that shade computed for it to its path. With
 * WP_MIRROR_NEE, mirror_shadow (launched after it) tests the two-leg rays
 * through planar mirrors of the mirror queue (kernels/mirror_light.h). */
#include "mirror_light.h"
#include "stage.h"
#include "traverse.h"

__kernel void shadow(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    int queued = index < launch.count;
    if (!WP_TRACE_SURPLUS_ITEMS && !queued)
        return;
    WP_SCENE_VIEW(scene);
    wp_uint slot = queued ? shadow_queue[index] : 0u;

    /* Scalar loads and a per-component update keep vector instructions out
     * of the stage, so that it vectorises (traverse.h). The direction's w is
     * the segment's length. */
    int blocked =
        wp_shadow_occluded(&scene, wp_load_xyz(shadow_origin, slot),
                           wp_load_xyz(shadow_direction, slot), wp_load_w(shadow_direction, slot));
    if (queued && !blocked) {
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
    if (!wp_shadow_occluded(scene, ray->origin, ray->direction, ray->length)) {
        __global float* sum = (__global float*)(radiance + slot);
        sum[0] += ray->contribution.x;
        sum[1] += ray->contribution.y;
        sum[2] += ray->contribution.z;
    }
}

#if WP_MIRROR_NEE
/* The same for a two-leg ray through a planar mirror (mirror_shadow below,
 * for the fused kernels). */
static inline void wp_trace_mirror_shadow_ray(const WpSceneView* scene, const WpMirrorShadow* ray,
                                              __global float4* radiance, wp_uint slot) {
    int blocked = wp_shadow_occluded(scene, ray->origin.xyz, ray->direction.xyz, ray->direction.w);
    blocked |= wp_shadow_occluded(scene, ray->origin2.xyz, ray->direction2.xyz, ray->direction2.w);
    if (!blocked) {
        __global float* sum = (__global float*)(radiance + slot);
        sum[0] += ray->contribution.x;
        sum[1] += ray->contribution.y;
        sum[2] += ray->contribution.z;
    }
}
#endif

#if WP_MIRROR_NEE
/* The mirror queue's two-leg shadow rays, in a kernel of their own (not a
 * stage of its own: the integrator launches it after shadow, under the
 * shadow stage's name), so that shadow stays as it was and vectorises. */
__kernel void mirror_shadow(WP_STAGE_PARAMETERS) {
    wp_uint index = get_global_id(0);
    int queued = index < launch.count;
    if (!WP_TRACE_SURPLUS_ITEMS && !queued)
        return;
    wp_uint slot = queued ? shadow_queue[frame.pool_size + index] : 0u;
    WP_SCENE_VIEW(scene);
    int blocked = wp_shadow_occluded(&scene, wp_load_xyz(mirror_shadow_origin, slot),
                                     wp_load_xyz(mirror_shadow_direction, slot),
                                     wp_load_w(mirror_shadow_direction, slot));
    blocked |= wp_shadow_occluded(&scene, wp_load_xyz(mirror_shadow_origin2, slot),
                                  wp_load_xyz(mirror_shadow_direction2, slot),
                                  wp_load_w(mirror_shadow_direction2, slot));
    if (queued && !blocked) {
        __global float* sum = (__global float*)(radiance + slot);
        __global const float* add = (__global const float*)(mirror_shadow_contribution + slot);
        sum[0] += add[0];
        sum[1] += add[1];
        sum[2] += add[2];
    }
}
#endif
