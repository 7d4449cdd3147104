/* Queries against the whole scene: the closest hit of a ray and whether
 * anything blocks a segment. Primitives are numbered triangles first, then
 * spheres; on an exact tie in t the lower number wins, so results never
 * depend on evaluation order.
 *
 * The scene is small enough (tens of primitives) that a linear loop beats a
 * hierarchy; see docs/architecture.md.
 */
#ifndef WP_TRAVERSE_H
#define WP_TRAVERSE_H

#include "scene_features.h"
#include "geometry.h"

/* Closest hit with 0 < t < t_max. Returns the primitive number or WP_NO_HIT. */
static inline wp_uint wp_closest_hit(float3 origin, float3 direction, float t_max,
                                     __global const WpTriangle* triangles,
                                     __global const WpSphere* spheres, WpFrame frame, float* t_hit) {
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
#if WP_HAS_TRIANGLES
    WpShearedRay ray = wp_shear_ray(origin, direction);
    for (wp_uint i = 0; i < frame.triangle_count; ++i) {
        float t;
        if (wp_intersect_triangle(&ray, triangles[i].v0.xyz, triangles[i].v1.xyz,
                                  triangles[i].v2.xyz, closest, &t)) {
            closest = t;
            hit = i;
        }
    }
#endif
#if WP_HAS_SPHERES
    for (wp_uint i = 0; i < frame.sphere_count; ++i) {
        float t;
        if (wp_intersect_sphere(origin, direction, spheres[i].center_radius, closest, &t)) {
            closest = t;
            hit = frame.triangle_count + i;
        }
    }
#endif
    *t_hit = closest;
    return hit;
}

/* 1 if any primitive lies on the segment origin + t * direction, 0 < t < t_max. */
static inline int wp_occluded(float3 origin, float3 direction, float t_max,
                              __global const WpTriangle* triangles,
                              __global const WpSphere* spheres, WpFrame frame) {
#if WP_HAS_TRIANGLES
    WpShearedRay ray = wp_shear_ray(origin, direction);
    for (wp_uint i = 0; i < frame.triangle_count; ++i) {
        float t;
        if (wp_intersect_triangle(&ray, triangles[i].v0.xyz, triangles[i].v1.xyz,
                                  triangles[i].v2.xyz, t_max, &t))
            return 1;
    }
#endif
#if WP_HAS_SPHERES
    for (wp_uint i = 0; i < frame.sphere_count; ++i) {
        float t;
        if (wp_intersect_sphere(origin, direction, spheres[i].center_radius, t_max, &t))
            return 1;
    }
#endif
    return 0;
}

#endif /* WP_TRAVERSE_H */
