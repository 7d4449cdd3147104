/* Queries against the whole scene: the closest hit of a ray and whether
 * anything blocks a segment. Primitives are numbered triangles first, then
 * spheres; on an exact tie in t the lower number wins, so results never
 * depend on evaluation order.
 *
 * The loops run over the frame's primitive counts, or, when the program is
 * specialised for a small scene (-D WP_TRIANGLE_COUNT=n -D WP_SPHERE_COUNT=m,
 * see src/render/device_scene.cpp and docs/specialization.md), over counts
 * fixed at compile time, fully unrolled. Both forms run the same tests of
 * geometry.h in the same order with the same limits, so they give
 * bit-identical results. Past a few hundred primitives a hierarchy would
 * beat any linear loop; docs/specialization.md has the measurements.
 */
#ifndef WP_TRAVERSE_H
#define WP_TRAVERSE_H

#include "scene_features.h"
#include "geometry.h"

#if defined(WP_TRIANGLE_COUNT) != defined(WP_SPHERE_COUNT)
#error "WP_TRIANGLE_COUNT and WP_SPHERE_COUNT are defined together or not at all"
#endif

#ifdef WP_TRIANGLE_COUNT
#define WP_TRIANGLE_LOOP_COUNT ((wp_uint)(WP_TRIANGLE_COUNT))
#define WP_SPHERE_LOOP_COUNT ((wp_uint)(WP_SPHERE_COUNT))
#define WP_TRAVERSE_UNROLL _Pragma("unroll")
#else
#define WP_TRIANGLE_LOOP_COUNT frame.triangle_count
#define WP_SPHERE_LOOP_COUNT frame.sphere_count
#define WP_TRAVERSE_UNROLL
#endif

/* Closest hit with 0 < t < t_max. Returns the primitive number or WP_NO_HIT. */
static inline wp_uint wp_closest_hit(float3 origin, float3 direction, float t_max,
                                     __global const WpTriangle* triangles,
                                     __global const WpSphere* spheres, WpFrame frame, float* t_hit) {
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
#if WP_HAS_TRIANGLES
    WpShearedRay ray = wp_shear_ray(origin, direction);
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_TRIANGLE_LOOP_COUNT; ++i) {
        float t;
        if (wp_intersect_triangle(&ray, triangles[i].v0.xyz, triangles[i].v1.xyz,
                                  triangles[i].v2.xyz, closest, &t)) {
            closest = t;
            hit = i;
        }
    }
#endif
#if WP_HAS_SPHERES
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_SPHERE_LOOP_COUNT; ++i) {
        float t;
        if (wp_intersect_sphere(origin, direction, spheres[i].center_radius, closest, &t)) {
            closest = t;
            hit = WP_TRIANGLE_LOOP_COUNT + i;
        }
    }
#endif
    (void)frame;
    *t_hit = closest;
    return hit;
}

/* 1 if any primitive lies on the segment origin + t * direction, 0 < t < t_max. */
static inline int wp_occluded(float3 origin, float3 direction, float t_max,
                              __global const WpTriangle* triangles,
                              __global const WpSphere* spheres, WpFrame frame) {
#if WP_HAS_TRIANGLES
    WpShearedRay ray = wp_shear_ray(origin, direction);
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_TRIANGLE_LOOP_COUNT; ++i) {
        float t;
        if (wp_intersect_triangle(&ray, triangles[i].v0.xyz, triangles[i].v1.xyz,
                                  triangles[i].v2.xyz, t_max, &t))
            return 1;
    }
#endif
#if WP_HAS_SPHERES
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_SPHERE_LOOP_COUNT; ++i) {
        float t;
        if (wp_intersect_sphere(origin, direction, spheres[i].center_radius, t_max, &t))
            return 1;
    }
#endif
    (void)frame;
    return 0;
}

#endif /* WP_TRAVERSE_H */
