// The naive intersection tests the stability suite measures the renderer's
// against (docs/stability.md), as OpenCL C for test kernels only: the
// production headers carry none of this.
//
//   Moller-Trumbore (1997) triangles, both faces, rejecting only det == 0:
//   each triangle computes its barycentrics from its own edge vectors, so two
//   triangles sharing an edge round differently and a ray through the edge
//   can miss both.
//
//   The textbook sphere quadratic: b^2 - 4ac cancels catastrophically when
//   the sphere is small and far (b^2 and 4ac agree in every float digit), and
//   -b + sqrt(...) cancels for the near root.
//
// A test kernel's source is kNaiveTraversalSource followed by its own; it
// calls st_closest_hit / st_occluded, which are the renderer's
// wp_closest_hit / wp_occluded unless the kernel is built with
// -D ST_NAIVE=1, and st_scene_view to describe a scene of triangles and
// spheres.
#pragma once

namespace wp::stability {

inline const char* kNaiveTraversalSource = R"CLC(
#include "traverse.h"

#ifndef ST_NAIVE
#define ST_NAIVE 0
#endif

static inline int st_naive_intersect_triangle(float3 origin, float3 direction, float3 p0,
                                              float3 p1, float3 p2, float t_max, float* t) {
    float3 e1 = p1 - p0, e2 = p2 - p0;
    float3 pv = cross(direction, e2);
    float det = dot(e1, pv);
    if (det == 0.0f)
        return 0;
    float inv_det = 1.0f / det;
    float3 s = origin - p0;
    float bu = dot(s, pv) * inv_det;
    if (bu < 0.0f || bu > 1.0f)
        return 0;
    float3 qv = cross(s, e1);
    float bv = dot(direction, qv) * inv_det;
    if (bv < 0.0f || bu + bv > 1.0f)
        return 0;
    float naive_t = dot(e2, qv) * inv_det;
    if (!(naive_t > 0.0f && naive_t < t_max))
        return 0;
    *t = naive_t;
    return 1;
}

static inline int st_naive_intersect_sphere(float3 origin, float3 direction, float4 center_radius,
                                            float t_max, float* t) {
    float3 f = origin - center_radius.xyz;
    float a = dot(direction, direction);
    float b = 2.0f * dot(f, direction);
    float c = dot(f, f) - center_radius.w * center_radius.w;
    float discriminant = b * b - 4.0f * a * c;
    if (discriminant < 0.0f)
        return 0;
    float root = sqrt(discriminant);
    float t_near = (-b - root) / (2.0f * a);
    float t_far = (-b + root) / (2.0f * a);
    float naive_hit = (t_near > 0.0f) ? t_near : t_far;
    if (!(naive_hit > 0.0f && naive_hit < t_max))
        return 0;
    *t = naive_hit;
    return 1;
}

/* The renderer's traversal order and tie rule, with the naive tests. */
static inline wp_uint st_naive_closest_hit(const WpSceneView* scene, float3 origin,
                                           float3 direction, float t_max, float* t_hit) {
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
    for (wp_uint i = 0; i < scene->triangle_count; ++i) {
        float t;
        if (st_naive_intersect_triangle(origin, direction, scene->triangles[i].v0.xyz,
                                        scene->triangles[i].v1.xyz, scene->triangles[i].v2.xyz,
                                        closest, &t)) {
            closest = t;
            hit = i;
        }
    }
    for (wp_uint i = 0; i < scene->sphere_count; ++i) {
        float t;
        if (st_naive_intersect_sphere(origin, direction, scene->spheres[i].center_radius, closest,
                                      &t)) {
            closest = t;
            hit = scene->triangle_count + i;
        }
    }
    *t_hit = closest;
    return hit;
}

static inline int st_naive_occluded(const WpSceneView* scene, float3 origin, float3 direction,
                                    float t_max) {
    float t;
    return st_naive_closest_hit(scene, origin, direction, t_max, &t) != WP_NO_HIT;
}

#if ST_NAIVE
#define st_closest_hit st_naive_closest_hit
#define st_occluded st_naive_occluded
#else
#define st_closest_hit wp_closest_hit
#define st_occluded wp_occluded
#endif

/* A scene of triangles and spheres only (no materials or lights). */
static inline WpSceneView st_scene_view(__global const WpTriangle* triangles,
                                        wp_uint triangle_count, __global const WpSphere* spheres,
                                        wp_uint sphere_count) {
    WpSceneView scene;
    scene.triangles = triangles;
    scene.spheres = spheres;
    scene.materials = 0;
    scene.lights = 0;
    scene.bvh_nodes = 0;
    scene.triangle_count = triangle_count;
    scene.sphere_count = sphere_count;
    scene.light_count = 0u;
    scene.light_area = 0.0f;
    return scene;
}
)CLC";

} // namespace wp::stability
