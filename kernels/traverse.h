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
 *
 * Vectorisation. PoCL runs a work-group as a loop over its work-items and
 * vectorises that loop (one ray per SIMD lane) only if its body holds no
 * vector-typed instruction and no branch it cannot turn into a select. So,
 * with fixed counts, the loops below select instead of branching, any-hit
 * is a closest hit bounded by t_max (an early exit would be a branch, and the
 * shrinking bound chains each test to the last, so that LLVM's SLP
 * vectoriser cannot pack neighbouring tests into short vectors either), the
 * tests are written on scalars (triangle.h, sphere.h), rays are loaded with
 * scalar loads (wp_load_xyz), and the entry points are always inlined (past
 * about 30 primitives the inliner would keep them out of line, and the call
 * would pass float3). tests/app/test_vectorised_stages.cpp checks the result.
 */
#ifndef WP_TRAVERSE_H
#define WP_TRAVERSE_H

#include "bvh.h"
#include "bvh_any_hit.h"
#include "primitive.h"
#include "sphere.h"
#include "triangle.h"

#ifdef WP_TRIANGLE_COUNT
#define WP_TRAVERSE_UNROLL _Pragma("unroll")
/* A fully unrolled loop vectorises only without early exits. */
#define WP_ANY_HIT_EARLY_EXIT 0
#else
#define WP_TRAVERSE_UNROLL
/* A loop over a runtime count does not vectorise anyway: stop at the first hit. */
#define WP_ANY_HIT_EARLY_EXIT 1
#endif

/* Work-items past the end of their queue (the last work-group's surplus;
 * for intersect also the rays the host's bound allowed for but the queue
 * did not get). Where the stage vectorises (fixed counts), whatever such an item skips
 * under `if (index < count)` becomes predicated, and a predicated load of
 * the scene, the same address in every lane, becomes a masked gather: nine
 * per triangle test, each as costly as eight loads (PoCL 3.1 on AVX-512).
 * So there surplus items trace slot 0's ray too and only their stores are
 * skipped: every scene load is then unconditional, one load for all lanes.
 * Where the stage does not vectorise, they leave at once. */
#ifdef WP_TRIANGLE_COUNT
#define WP_TRACE_SURPLUS_ITEMS 1
#else
#define WP_TRACE_SURPLUS_ITEMS 0
#endif

/* xyz of entry `index` of a float4 buffer, as three scalar loads: a float4
 * load (as `buffer[index].x` compiles to) would be a vector instruction in
 * the stage's body. */
static inline WP_ALWAYS_INLINE float3 wp_load_xyz(__global const float4* buffer, wp_uint index) {
    __global const float* entry = (__global const float*)(buffer + index);
    return (float3)(entry[0], entry[1], entry[2]);
}

/* w of entry `index` of a float4 buffer, as one scalar load. */
static inline WP_ALWAYS_INLINE float wp_load_w(__global const float4* buffer, wp_uint index) {
    return ((__global const float*)(buffer + index))[3];
}

/* Shadow culling (src/render/shadow_occluders.hpp): with fixed counts the
 * host may name the triangles that can block a segment between two points of
 * the scene's surfaces, leaving out the bounding faces (a closed convex
 * room's walls), which cannot: WP_SHADOW_OCCLUDER_COUNT of them, listed in
 * WP_SHADOW_OCCLUDERS. The list is a constant table, so in the unrolled loop
 * each entry folds into its load's address. */
#if defined(WP_TRIANGLE_COUNT) && defined(WP_SHADOW_OCCLUDER_COUNT) && !WP_USE_BVH
#define WP_SHADOW_CULLING 1
#if WP_SHADOW_OCCLUDER_COUNT > 0
__constant wp_uint wp_shadow_occluder_table[WP_SHADOW_OCCLUDER_COUNT] = {WP_SHADOW_OCCLUDERS};
#define WP_SHADOW_OCCLUDER(k) wp_shadow_occluder_table[k]
#else
#define WP_SHADOW_OCCLUDER(k) (k)
#endif
#else
#define WP_SHADOW_CULLING 0
#define WP_SHADOW_OCCLUDER_COUNT 0
#define WP_SHADOW_OCCLUDER(k) (k)
#endif

/* The primitives on the ray origin + t direction, 0 < t < t_max: the closest
 * one, or with any_hit (a compile-time constant wherever it is called) some
 * one of them: without fixed counts the first one found, without shrinking
 * t_max; with them the closest. With `culled` (any-hit only, a compile-time
 * constant too) only the triangles of the shadow culling list are tested.
 * Returns the primitive number or WP_NO_HIT, and the hit's t in *t_hit
 * (t_max on a miss). */
static inline WP_ALWAYS_INLINE wp_uint wp_loop_trace(const WpSceneView* scene, float3 origin,
                                                     float3 direction, float t_max, int any_hit,
                                                     int culled, float* t_hit) {
    WpShearedRay ray = wp_shear_ray(origin, direction);
    /* The ray's own components again, taken back out of the sheared frame:
     * the same values, but no longer from consecutive loads, which is what
     * would let SLP pack the sphere test's alike x, y and z lines. */
    float ox = ray.kx == 0 ? ray.ox : (ray.ky == 0 ? ray.oy : ray.oz);
    float oy = ray.ky == 1 ? ray.oy : (ray.kz == 1 ? ray.oz : ray.ox);
    float oz = ray.kz == 2 ? ray.oz : (ray.kx == 2 ? ray.ox : ray.oy);
    float dx = ray.kx == 0 ? ray.dx : (ray.ky == 0 ? ray.dy : ray.dz);
    float dy = ray.ky == 1 ? ray.dy : (ray.kz == 1 ? ray.dz : ray.dx);
    float dz = ray.kz == 2 ? ray.dz : (ray.kx == 2 ? ray.dx : ray.dy);
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
#if WP_HAS_TRIANGLES
    const int skip_faces = WP_SHADOW_CULLING && culled && any_hit;
    const wp_uint triangle_tests =
        skip_faces ? (wp_uint)WP_SHADOW_OCCLUDER_COUNT : WP_TRIANGLE_LOOP_COUNT(scene);
    WP_TRAVERSE_UNROLL
    for (wp_uint k = 0; k < triangle_tests; ++k) {
        wp_uint i = skip_faces ? (wp_uint)WP_SHADOW_OCCLUDER(k) : k;
        __global const WpTriangle* triangle = &scene->triangles[i];
        float3 p0 = wp_load_xyz(&triangle->v0, 0), p1 = wp_load_xyz(&triangle->v1, 0),
               p2 = wp_load_xyz(&triangle->v2, 0);
        float t;
        int found = wp_triangle_test(&ray, p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z,
                                     closest, &t);
        closest = found ? t : closest;
        hit = found ? i : hit;
        if (WP_ANY_HIT_EARLY_EXIT && any_hit && found)
            break;
    }
#endif
#if WP_HAS_SPHERES
    WP_TRAVERSE_UNROLL
    for (wp_uint i = 0; i < WP_SPHERE_LOOP_COUNT(scene); ++i) {
        if (WP_ANY_HIT_EARLY_EXIT && any_hit && hit != WP_NO_HIT)
            break;
        float3 centre = wp_load_xyz(&scene->spheres[i].center_radius, 0);
        float radius = wp_load_w(&scene->spheres[i].center_radius, 0);
        /* The sphere as seen through the running bound: the sphere itself,
         * since the bound is never negative (and with a negative one no t
         * can pass 0 < t < bound, whatever the sphere). It makes each test
         * depend on the last, so that SLP cannot pack the alike lines of
         * neighbouring spheres' tests. */
        int open = !(closest < 0.0f);
        float t;
        int found =
            wp_sphere_test(ox, oy, oz, dx, dy, dz, open ? centre.x : 0.0f, open ? centre.y : 0.0f,
                           open ? centre.z : 0.0f, open ? radius : 0.0f, closest, &t);
        closest = found ? t : closest;
        hit = found ? wp_sphere_primitive(scene, i) : hit;
    }
#endif
    (void)ox, (void)oy, (void)oz, (void)dx, (void)dy, (void)dz, (void)any_hit, (void)culled;
    *t_hit = closest;
    return hit;
}

static inline WP_ALWAYS_INLINE wp_uint wp_trace(const WpSceneView* scene, float3 origin,
                                                float3 direction, float t_max, int any_hit,
                                                int culled, float* t_hit) {
#if WP_USE_BVH
    /* A closest hit answers an any-hit query too (the hierarchy's own
     * any-hit traversal is wp_occluded's, below). */
    (void)culled, (void)any_hit;
    return wp_bvh_trace(scene, origin, direction, t_max, t_hit);
#else
    return wp_loop_trace(scene, origin, direction, t_max, any_hit, culled, t_hit);
#endif
}

/* Closest hit with 0 < t < t_max. Returns the primitive number or WP_NO_HIT. */
static inline WP_ALWAYS_INLINE wp_uint wp_closest_hit(const WpSceneView* scene, float3 origin,
                                                      float3 direction, float t_max, float* t_hit) {
    return wp_trace(scene, origin, direction, t_max, 0, 0, t_hit);
}

/* 1 if any primitive lies on the segment origin + t * direction, 0 < t < t_max.
 * Through a hierarchy, its own traversal (bvh_any_hit.h). */
static inline WP_ALWAYS_INLINE int wp_occluded(const WpSceneView* scene, float3 origin,
                                               float3 direction, float t_max) {
#if WP_USE_BVH
    return wp_bvh_occluded(scene, origin, direction, t_max);
#else
    float t;
    return wp_loop_trace(scene, origin, direction, t_max, 1, 0, &t) != WP_NO_HIT;
#endif
}

/* The same for a shadow ray: a segment between two points of the scene's
 * surfaces (its origin offset from the first), which with shadow culling
 * skips the faces that cannot block it. The shadow stages call this. */
static inline WP_ALWAYS_INLINE int wp_shadow_occluded(const WpSceneView* scene, float3 origin,
                                                      float3 direction, float t_max) {
#if WP_USE_BVH
    return wp_bvh_occluded(scene, origin, direction, t_max);
#else
    float t;
    return wp_loop_trace(scene, origin, direction, t_max, 1, 1, &t) != WP_NO_HIT;
#endif
}

#endif /* WP_TRAVERSE_H */
