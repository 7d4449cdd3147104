/* What a primitive number means, and the surface a ray hit.
 *
 * Primitives are numbered triangles first, then spheres: triangle i is
 * primitive i, sphere j is primitive triangle_count + j. This file is the
 * only place that decodes a number (traverse.h, the only place that makes
 * them, numbers them the same way); a new shape gets its kind here and its
 * surface record below.
 */
#ifndef WP_PRIMITIVE_H
#define WP_PRIMITIVE_H

#include "ray_offset.h"
#include "scene_features.h"
#include "sphere.h"
#include "stage.h"
#include "triangle.h"

#define WP_PRIMITIVE_TRIANGLE 0u
#define WP_PRIMITIVE_SPHERE 1u

/* The loops over primitives run over the scene's counts, or, when the
 * program is specialised for a small scene (-D WP_TRIANGLE_COUNT=n
 * -D WP_SPHERE_COUNT=m, see src/render/device_scene.cpp and
 * docs/specialization.md), over counts fixed at compile time. */
#if defined(WP_TRIANGLE_COUNT) != defined(WP_SPHERE_COUNT)
#error "WP_TRIANGLE_COUNT and WP_SPHERE_COUNT are defined together or not at all"
#endif
#ifdef WP_TRIANGLE_COUNT
#define WP_TRIANGLE_LOOP_COUNT(scene) ((wp_uint)(WP_TRIANGLE_COUNT))
#define WP_SPHERE_LOOP_COUNT(scene) ((wp_uint)(WP_SPHERE_COUNT))
#else
#define WP_TRIANGLE_LOOP_COUNT(scene) ((scene)->triangle_count)
#define WP_SPHERE_LOOP_COUNT(scene) ((scene)->sphere_count)
#endif

static inline wp_uint wp_sphere_primitive(const WpSceneView* scene, wp_uint sphere) {
    return WP_TRIANGLE_LOOP_COUNT(scene) + sphere;
}

static inline wp_uint wp_primitive_kind(const WpSceneView* scene, wp_uint primitive) {
#if WP_HAS_SPHERES
    if (primitive >= scene->triangle_count)
        return WP_PRIMITIVE_SPHERE;
#endif
    (void)scene;
    (void)primitive;
    return WP_PRIMITIVE_TRIANGLE;
}

/* The ray test of one primitive: 1 and *t if the ray hits it at
 * 0 < t < t_max. `sheared` is the triangle test's form of the same ray. */
static inline int wp_intersect_primitive(const WpSceneView* scene, const WpShearedRay* sheared,
                                         float3 origin, float3 direction, wp_uint primitive,
                                         float t_max, float* t) {
#if WP_HAS_SPHERES
    if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_SPHERE)
        return wp_intersect_sphere(origin, direction,
                                   scene->spheres[primitive - scene->triangle_count].center_radius,
                                   t_max, t);
#endif
#if WP_HAS_TRIANGLES
    __global const WpTriangle* triangle = &scene->triangles[primitive];
    return wp_intersect_triangle(sheared, triangle->v0.xyz, triangle->v1.xyz, triangle->v2.xyz,
                                 t_max, t);
#else
    (void)sheared, (void)origin, (void)direction, (void)primitive, (void)t_max, (void)t;
    return 0;
#endif
}

/* Where a ray met a surface, as shading needs it. */
typedef struct {
    float3 position; /* on the surface: its error scales with the surface's coordinates */
    float3 normal;   /* geometric, unit, the primitive's front side */
    float scale;     /* magnitude of the primitive's coordinates, for ray offsets */
    wp_uint material;
    int front_face; /* the ray arrived on the front side */
    /* The primitive is a closed solid (a sphere) and the ray met it from
     * inside: only an offset origin that landed inside one can (next to a
     * contact point, docs/stability.md case 4). */
    int inside_solid;
} WpSurface;

/* The surface of `primitive` where the ray origin + t direction hit it. The
 * hit point is reprojected onto the surface, so that its error scales with
 * the surface's coordinates, not with t. */
static inline WpSurface wp_surface_at(const WpSceneView* scene, wp_uint primitive, float3 origin,
                                      float3 direction, float t) {
    WpSurface s;
    float3 position = origin + t * direction;
    s.inside_solid = 0;
#if WP_HAS_SPHERES
    if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_SPHERE) {
        WpSphere sphere = scene->spheres[primitive - scene->triangle_count];
        s.normal = normalize(position - sphere.center_radius.xyz);
        s.position = sphere.center_radius.xyz + sphere.center_radius.w * s.normal;
        s.scale = wp_sphere_scale(sphere.center_radius);
        s.material = sphere.material;
        s.inside_solid = dot(direction, s.normal) >= 0.0f;
    } else
#endif
    {
        WpTriangle triangle = scene->triangles[primitive];
        s.normal = normalize(wp_triangle_normal(&triangle));
        s.position = position - dot(position - triangle.v0.xyz, s.normal) * s.normal;
        s.scale = wp_triangle_scale(&triangle);
        s.material = triangle.material;
    }
    s.front_face = dot(direction, s.normal) < 0.0f;
    return s;
}

#endif /* WP_PRIMITIVE_H */
