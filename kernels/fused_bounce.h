/* One bounce of a path in one work-item, as the fused kernels run it
 * (bounce.cl, wave.cl, tail.cl): the closest hit of the slot's ray, shade,
 * then the shadow rays shade made, traced at once. The same functions in the
 * same order as the stages plan's intersect, shade, shadow and mirror_shadow
 * kernels, so a path's radiance is that plan's float for float; only the
 * closest hit stays in registers instead of going through hit_t and
 * hit_primitive, and a shadow ray is traced instead of queued.
 *
 * Returns shade's outcome (WP_SHADED_*) and adds the shadow rays traced to
 * *shadows (a mirror's two legs count two, as the stages plan counts them);
 * the caller counts them into its counters as it sees fit. */
#ifndef WP_FUSED_BOUNCE_H
#define WP_FUSED_BOUNCE_H

#include "shade.cl"
#include "shadow.cl"
#include "stage.h"
#include "traverse.h"

static inline WP_ALWAYS_INLINE int wp_fused_bounce(WP_STAGE_PARAMETERS, const WpSceneView* scene,
                                                   wp_uint slot, wp_uint* shadows) {
    /* Drawn before the traversal, which hides their latency (shade.cl). */
    float4 first, second;
    wp_shade_numbers(frame, path_pixel, path_sample, path_depth, slot, &first, &second);
    float t;
    wp_uint primitive = wp_closest_hit(scene, wp_load_xyz(ray_origin, slot),
                                       wp_load_xyz(ray_direction, slot), INFINITY, &t);
    WpShadowRay shadow;
    int outcome = wp_shade_path(WP_STAGE_ARGUMENTS, slot, primitive, t, first, second, &shadow);
    if (shadow.made) {
        ++*shadows;
        wp_trace_shadow_ray(scene, &shadow, radiance, slot);
    }
#if WP_MIRROR_NEE /* after the plain one, as the stages plan adds them */
    if (shadow.mirror_made) {
        *shadows += 2u;
        wp_trace_mirror_shadow_ray(scene, &shadow.mirror, radiance, slot);
    }
#endif
    return outcome;
}

#endif /* WP_FUSED_BOUNCE_H */
