/* What a primitive number means, and the surface a ray hit.
 *
 * Primitives are numbered triangles first, then spheres: triangle i is
 * primitive i, sphere j is primitive triangle_count + j, and past them the
 * triangles of instances (WP_PRIMITIVE_INSTANCE). This file is the
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
#include "tangent.h"
#include "triangle.h"
#if WP_TRACE_INSTANCES
#include "instance.h"
#endif

#define WP_PRIMITIVE_TRIANGLE 0u
#define WP_PRIMITIVE_SPHERE 1u
/* A triangle of an instance's shape group (instance.h): numbered after the
 * spheres, not a triangle of triangles[], and never a light or a planar
 * mirror of the host's tables (groups hold no emitters; a path off an
 * instanced mirror keeps the weight of any delta bounce). */
#define WP_PRIMITIVE_INSTANCE 2u

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
#if WP_TRACE_INSTANCES
    if (primitive >= scene->triangle_count + scene->sphere_count)
        return WP_PRIMITIVE_INSTANCE;
#endif
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
    /* Unit, on the side of `normal`: the interpolated vertex normals of a
     * triangle that has them (WP_HAS_SHADING_NORMALS), else `normal`. */
    float3 shading_normal;
    int smooth; /* shading_normal is interpolated (not the geometric normal) */
    /* Where rays leave the surface from: `position`, or with shading normals
     * the point lifted off the flat triangle towards the smooth surface its
     * vertex normals describe (wp_terminator_point). */
    float3 spawn_front; /* for a ray leaving by the front side */
    float3 spawn_back;
#if WP_HAS_TEXTURES
    /* Texture coordinates, as Mitsuba 3 parameterises each shape (measured
     * with its ray_intersect): a triangle's interpolated vertex (u, v), or
     * without them its barycentrics (b1, b2); a sphere's
     * (phi / 2 pi, theta / pi) about its centre, phi from +x towards +y in
     * [0, 2 pi), theta from +z. Read them through wp_surface_uv: a sphere's
     * are left 0 here and computed there, only where a texture needs them. */
    float2 uv;
#endif
#if WP_HAS_ANISOTROPY
    /* The direction alpha_u of an anisotropic BSDF runs along, before it is
     * made perpendicular to the shading normal (tangent.h, bsdf/frame.h). */
    float3 dp_du;
#endif
} WpSurface;

#if WP_HAS_TEXTURES
/* The barycentric coordinates (b1, b2) of `position`, a point on the
 * triangle's plane, from the sub-triangles' areas. */
static inline float2 wp_triangle_barycentrics(const WpTriangle* t, float3 position) {
    float3 e1 = t->v1.xyz - t->v0.xyz, e2 = t->v2.xyz - t->v0.xyz, w = position - t->v0.xyz;
    float3 ng = cross(e1, e2);
    float inverse_area = 1.0f / dot(ng, ng);
    return (float2)(dot(cross(w, e2), ng) * inverse_area, dot(cross(e1, w), ng) * inverse_area);
}

static inline float2 wp_triangle_uv(const WpSceneView* scene, const WpTriangle* t,
                                    float3 position) {
    float2 b = wp_triangle_barycentrics(t, position);
    wp_uint uvs = wp_triangle_uvs(t);
    if (uvs == 0u)
        return b;
    WpTriangleUvs c = scene->triangle_uvs[uvs - 1u];
    float b0 = 1.0f - b.x - b.y;
    return (float2)(b0 * c.u.x + b.x * c.u.y + b.y * c.u.z, b0 * c.v.x + b.x * c.v.y + b.y * c.v.z);
}

/* A sphere's texture coordinates at unit normal n (the direction from its
 * centre). */
static inline float2 wp_sphere_uv(float3 n) {
    float phi = atan2(n.y, n.x);
    phi = phi < 0.0f ? phi + 2.0f * M_PI_F : phi;
    return (float2)(phi * (0.5f * M_1_PI_F), acos(clamp(n.z, -1.0f, 1.0f)) * M_1_PI_F);
}
#endif

#if WP_HAS_SHADING_NORMALS
/* The shadow terminator fix (Hanika, "Hacking the shadow terminator", Ray
 * Tracing Gems II, 2021). Shading normals make a coarse mesh look smooth, but
 * rays still start on its flat facets, from which the neighbouring facets
 * block light that the smooth surface would receive: a jagged dark band along
 * the terminator. The fix moves the ray origin from p towards the surface the
 * vertex normals describe: for each vertex i, p projected onto the tangent
 * plane at v_i when p lies below it, blended with the barycentrics,
 *     p' = p + sum_i b_i max(0, -dot(p - v_i, n_i)) n_i,
 * with the normals on the side the ray leaves by. It only ever lifts p, by at
 * most the facets' deviation from the smooth surface. */
static inline float3 wp_terminator_point(float3 p, float3 b, const WpTriangle* t,
                                         const WpShadingNormals* n, float side) {
#if WP_SHADOW_TERMINATOR_FIX
    float3 n0 = side * n->n0.xyz, n1 = side * n->n1.xyz, n2 = side * n->n2.xyz;
    float d0 = fmax(0.0f, -dot(p - t->v0.xyz, n0));
    float d1 = fmax(0.0f, -dot(p - t->v1.xyz, n1));
    float d2 = fmax(0.0f, -dot(p - t->v2.xyz, n2));
    return p + (b.x * d0) * n0 + (b.y * d1) * n1 + (b.z * d2) * n2;
#else
    (void)b, (void)t, (void)n, (void)side;
    return p;
#endif
}

/* The shading normal and the spawn points of a hit on triangle t with vertex
 * normals `normals` (unit, in t's frame); s->position is already on the
 * triangle's plane. */
static inline void wp_shade_with_vertex_normals(const WpTriangle* t,
                                                const WpShadingNormals* normals, WpSurface* s) {
    WpShadingNormals n = *normals;
    /* Barycentrics of the hit point from the sub-triangles' areas. */
    float3 e1 = t->v1.xyz - t->v0.xyz, e2 = t->v2.xyz - t->v0.xyz, w = s->position - t->v0.xyz;
    float3 ng = cross(e1, e2);
    float inverse_area = 1.0f / dot(ng, ng);
    float b1 = dot(cross(w, e2), ng) * inverse_area;
    float b2 = dot(cross(e1, w), ng) * inverse_area;
    float3 b = (float3)(1.0f - b1 - b2, b1, b2);
    float3 shading = normalize(b.x * n.n0.xyz + b.y * n.n1.xyz + b.z * n.n2.xyz);
    /* The normals are the file's: keep them on the winding's side. */
    float side = dot(shading, s->normal) < 0.0f ? -1.0f : 1.0f;
    s->shading_normal = side * shading;
    s->smooth = 1;
    s->spawn_front = wp_terminator_point(s->position, b, t, &n, side);
    s->spawn_back = wp_terminator_point(s->position, b, t, &n, -side);
}
#endif

/* The material of `primitive`, without the rest of its surface record
 * (what shade's sort by material reads, kernels/shade_sort.cl). */
static inline wp_uint wp_primitive_material(const WpSceneView* scene, wp_uint primitive) {
#if WP_HAS_SPHERES
    if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_SPHERE)
        return scene->spheres[primitive - scene->triangle_count].material;
#endif
#if WP_TRACE_INSTANCES
    if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_INSTANCE) {
        wp_uint number, group_triangle;
        wp_instance_hit(scene, primitive, &number, &group_triangle);
        WpTriangle object = scene->group_triangles[group_triangle];
        return wp_triangle_material(&object);
    }
#endif
    WpTriangle triangle = scene->triangles[primitive];
    return wp_triangle_material(&triangle);
}

#if WP_HAS_TEXTURES
/* The texture coordinates of surface s on `primitive`. A triangle's are in
 * s->uv already (wp_surface_at); a sphere's are computed here from the
 * normal, only for the hits whose material is textured: their atan2 and acos
 * on every sphere hit were about 3.5 % of the showcase's shade, which
 * textures no sphere (docs/performance.md, "The showcase's shade, profiled and cut"). */
static inline float2 wp_surface_uv(const WpSceneView* scene, wp_uint primitive,
                                   const WpSurface* s) {
#if WP_HAS_SPHERES
    if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_SPHERE)
        return wp_sphere_uv(s->normal);
#else
    (void)scene, (void)primitive;
#endif
    return s->uv;
}
#endif

/* The surface of `primitive` where the ray origin + t direction hit it. The
 * hit point is reprojected onto the surface, so that its error scales with
 * the surface's coordinates, not with t. */
static inline void wp_surface_at(const WpSceneView* scene, wp_uint primitive, float3 origin,
                                 float3 direction, float t, WpSurface* out) {
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
#if WP_HAS_TEXTURES
        s.uv = (float2)(0.0f); /* wp_surface_uv's to compute, where a texture asks */
#endif
#if WP_HAS_ANISOTROPY
        s.dp_du = wp_sphere_dp_du(s.normal);
#endif
    } else
#endif
    {
#if WP_TRACE_INSTANCES
        WpTriangle triangle;
        __global const WpInstance* instance = 0;
        if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_INSTANCE) {
            wp_uint number, group_triangle;
            wp_instance_hit(scene, primitive, &number, &group_triangle);
            instance = &scene->instances[number];
            wp_instance_world_triangle(instance, &scene->group_triangles[group_triangle],
                                       &triangle);
        } else {
            triangle = scene->triangles[primitive];
        }
        /* A mirrored instance's front is its object normal's side, against
         * the world winding (Mitsuba's instance, measured). */
        s.normal = normalize(wp_triangle_normal(&triangle));
        if (instance && instance->mirrored)
            s.normal = -s.normal;
#else
        WpTriangle triangle = scene->triangles[primitive];
        s.normal = normalize(wp_triangle_normal(&triangle));
#endif
        s.position = position - dot(position - triangle.v0.xyz, s.normal) * s.normal;
        s.scale = wp_triangle_scale(&triangle);
        s.material = wp_triangle_material(&triangle);
#if WP_HAS_TEXTURES
        s.uv = wp_triangle_uv(scene, &triangle, s.position);
#endif
#if WP_HAS_ANISOTROPY
        s.dp_du = wp_triangle_dp_du(scene, &triangle, s.normal);
#endif
#if WP_HAS_SHADING_NORMALS
        if (wp_triangle_normals(&triangle) != 0u) {
            s.front_face = dot(direction, s.normal) < 0.0f;
            WpShadingNormals normals = scene->triangle_normals[wp_triangle_normals(&triangle) - 1u];
#if WP_TRACE_INSTANCES
            if (instance)
                wp_instance_world_normals(instance, &normals);
#endif
            wp_shade_with_vertex_normals(&triangle, &normals, &s);
            *out = s;
            return;
        }
#endif
    }
    s.front_face = dot(direction, s.normal) < 0.0f;
    s.shading_normal = s.normal;
    s.smooth = 0;
    s.spawn_front = s.position;
    s.spawn_back = s.position;
    *out = s;
}

#endif /* WP_PRIMITIVE_H */
