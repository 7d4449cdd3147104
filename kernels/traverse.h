/* Queries against the whole scene: the closest hit of a ray and whether
 * anything blocks a segment. The only entry points of ray traversal: the
 * intersect and shadow stages (and tests) call these two, so an acceleration
 * structure replaces their bodies and nothing else.
 *
 * Without a hierarchy (WP_USE_BVH=0, small scenes) every primitive is tested,
 * in number order: on an exact tie in t the lower number wins, so results
 * never depend on evaluation order. With one, bvh.h walks it. With the
 * counts fixed at compile time (primitive.h) the loops unroll fully; both forms run the same tests
 * in the same order with the same limits, so they give bit-identical results. Past a few hundred
 * primitives a hierarchy would beat any linear loop; docs/specialization.md has the measurements.
 */
#ifndef WP_TRAVERSE_H
#define WP_TRAVERSE_H

#include "bvh.h"
#include "primitive.h"
#include "sphere.h"
#include "triangle.h"

#ifdef WP_TRIANGLE_COUNT
#define WP_TRAVERSE_UNROLL _Pragma("unroll")
#else
#define WP_TRAVERSE_UNROLL
#endif

/* The primitives on the ray origin + t direction, 0 < t < t_max: the closest
 * one, or with any_hit (a compile-time constant wherever it is called) the
 * first one found, without shrinking t_max. Returns the primitive number or
 * WP_NO_HIT, and the hit's t in *t_hit (t_max on a miss). */
static inline wp_uint wp_loop_trace(const WpSceneView* scene, float3 origin, float3 direction,
                                    float t_max, int any_hit, float* t_hit) {
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
#if WP_HAS_TRIANGLES
    WpShearedRay ray = wp_shear_ray(origin, direction);
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_TRIANGLE_LOOP_COUNT(scene); ++i) {
        float t;
        if (wp_intersect_triangle(&ray, scene->triangles[i].v0.xyz, scene->triangles[i].v1.xyz,
                                  scene->triangles[i].v2.xyz, closest, &t)) {
            closest = t;
            hit = i;
            if (any_hit)
                break;
        }
    }
#endif
#if WP_HAS_SPHERES
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_SPHERE_LOOP_COUNT(scene); ++i) {
        if (any_hit && hit != WP_NO_HIT)
            break;
        float t;
        if (wp_intersect_sphere(origin, direction, scene->spheres[i].center_radius, closest, &t)) {
            closest = t;
            hit = wp_sphere_primitive(scene, i);
        }
    }
#endif
    (void)any_hit;
    *t_hit = closest;
    return hit;
}

static inline wp_uint wp_trace(const WpSceneView* scene, float3 origin, float3 direction,
                               float t_max, int any_hit, float* t_hit) {
#if WP_USE_BVH
    return wp_bvh_trace(scene, origin, direction, t_max, any_hit, t_hit);
#else
    return wp_loop_trace(scene, origin, direction, t_max, any_hit, t_hit);
#endif
}

/* Closest hit with 0 < t < t_max. Returns the primitive number or WP_NO_HIT. */
static inline wp_uint wp_closest_hit(const WpSceneView* scene, float3 origin, float3 direction,
                                     float t_max, float* t_hit) {
    return wp_trace(scene, origin, direction, t_max, 0, t_hit);
}

/* 1 if any primitive lies on the segment origin + t * direction, 0 < t < t_max. */
static inline int wp_occluded(const WpSceneView* scene, float3 origin, float3 direction,
                              float t_max) {
    float t;
    return wp_trace(scene, origin, direction, t_max, 1, &t) != WP_NO_HIT;
}

#endif /* WP_TRAVERSE_H */
