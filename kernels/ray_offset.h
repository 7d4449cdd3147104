/* Spawning rays off a surface without hitting it again.
 *
 * A spawned ray starts off its surface, along the normal on the side it
 * leaves by, so that rounding cannot make it hit the surface it left.
 *
 * The offset is relative: WP_RAY_OFFSET_RELATIVE times the magnitude of the
 * coordinates involved, which is the hit point and the primitive's own
 * vertices (or centre plus radius): the intersection test subtracts the ray
 * origin from the vertices, so its rounding error scales with both. A fixed
 * epsilon would be too big for a millimetre scene and too small for a
 * kilometre one; a relative one keeps the renderer scale-invariant. 2e-6 is
 * about 17 float ulps of that magnitude, above the few ulps of error of a
 * reprojected hit point and small enough that contact shadows stay closed.
 * (docs/stability.md measures it against a fixed 1e-4.)
 */
#ifndef WP_RAY_OFFSET_H
#define WP_RAY_OFFSET_H

#include "wp_shared.h"

#define WP_RAY_OFFSET_RELATIVE 2.0e-6f
/* Keeps the offset non-zero at the exact origin. */
#define WP_RAY_OFFSET_FLOOR 1.0e-30f

static inline float wp_max_abs_component(float3 p) {
    return fmax(fmax(fabs(p.x), fabs(p.y)), fabs(p.z));
}

/* How far to offset a point on a primitive whose coordinates reach `scale`
 * in magnitude (see wp_triangle_scale, wp_sphere_scale). */
static inline float wp_offset_distance(float3 p, float scale) {
    return WP_RAY_OFFSET_RELATIVE * fmax(wp_max_abs_component(p), scale) + WP_RAY_OFFSET_FLOOR;
}

/* Moves p off its surface to the side of `side_normal` (unit length). */
static inline float3 wp_offset_ray_origin(float3 p, float3 side_normal, float scale) {
    return p + side_normal * wp_offset_distance(p, scale);
}

static inline float wp_triangle_scale(const WpTriangle* t) {
    return fmax(wp_max_abs_component(t->v0.xyz),
                fmax(wp_max_abs_component(t->v1.xyz), wp_max_abs_component(t->v2.xyz)));
}

static inline float wp_sphere_scale(float4 center_radius) {
    return wp_max_abs_component(center_radius.xyz) + center_radius.w;
}

#endif /* WP_RAY_OFFSET_H */
