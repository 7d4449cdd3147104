/* Instances of shape groups (WP_HAS_INSTANCES, with WP_USE_BVH): the second
 * level of the hierarchy.
 *
 * A shape group's triangles are stored once, in object space
 * (group_triangles), under a hierarchy of their own (group_bvh_nodes); an
 * instance (WpInstance, wp_shared.h) places the group in the world by an
 * affine map. The top-level hierarchy (bvh.h) holds each instance as one
 * primitive whose box is the group's box mapped to the world; a ray that
 * reaches it is mapped into object space, origin and direction alike, and
 * the direction is not renormalised, so that a point at parameter t of the
 * object ray is the image of the point at t of the world ray: t stays the
 * world's t, and the closest hit found so far bounds the group's traversal
 * as it is. The surface (primitive.h) is built back in the world: the hit
 * triangle's vertices mapped to the world, its vertex normals mapped by the
 * inverse transpose and normalised, so that everything after intersect sees
 * world-space data.
 *
 * This file: the maps and the decoding of a hit, for primitive.h; the
 * traversal is instance_trace.h's. */
#ifndef WP_INSTANCE_H
#define WP_INSTANCE_H

#include "stage.h"
#include "triangle.h"

/* Row r of an affine map applied to point p: dot(row.xyz, p) + row.w. */
static inline float wp_affine_row(float4 row, float3 p) {
    return row.x * p.x + row.y * p.y + row.z * p.z + row.w;
}

/* The map's linear part applied to vector v. */
static inline float wp_linear_row(float4 row, float3 v) {
    return row.x * v.x + row.y * v.y + row.z * v.z;
}

static inline float3 wp_instance_to_world(__global const WpInstance* m, float3 p) {
    return (float3)(wp_affine_row(m->to_world[0], p), wp_affine_row(m->to_world[1], p),
                    wp_affine_row(m->to_world[2], p));
}

/* The world ray origin + t direction in object space: the same t reaches
 * the image of the same point (the direction is not renormalised). */
static inline void wp_instance_object_ray(__global const WpInstance* m, float3 origin,
                                          float3 direction, float3* object_origin,
                                          float3* object_direction) {
    *object_origin =
        (float3)(wp_affine_row(m->to_object[0], origin), wp_affine_row(m->to_object[1], origin),
                 wp_affine_row(m->to_object[2], origin));
    *object_direction = (float3)(wp_linear_row(m->to_object[0], direction),
                                 wp_linear_row(m->to_object[1], direction),
                                 wp_linear_row(m->to_object[2], direction));
}

/* An object-space normal in the world: by the inverse transpose of to_world,
 * the transpose of to_object's linear part (not normalised). */
static inline float3 wp_instance_normal_to_world(__global const WpInstance* m, float3 n) {
    return n.x * m->to_object[0].xyz + n.y * m->to_object[1].xyz + n.z * m->to_object[2].xyz;
}

/* The instance and the group triangle (in group_triangles) of an instanced
 * hit's primitive number: the last instance whose first_primitive is not
 * past it (the host numbers instances' hits in instance order). */
static inline void wp_instance_hit(const WpSceneView* scene, wp_uint primitive, wp_uint* instance,
                                   wp_uint* triangle) {
    wp_uint number = primitive - scene->triangle_count - scene->sphere_count;
    wp_uint low = 0u, high = scene->instance_count;
    while (high - low > 1u) {
        wp_uint middle = low + (high - low) / 2u;
        if (scene->instances[middle].first_primitive <= number)
            low = middle;
        else
            high = middle;
    }
    *instance = low;
    *triangle =
        scene->instances[low].first_triangle + (number - scene->instances[low].first_primitive);
}

/* The hit group triangle as a world-space triangle (its index lanes kept). */
static inline void wp_instance_world_triangle(__global const WpInstance* m,
                                              __global const WpTriangle* object, WpTriangle* out) {
    out->v0 = (float4)(wp_instance_to_world(m, object->v0.xyz), object->v0.w);
    out->v1 = (float4)(wp_instance_to_world(m, object->v1.xyz), object->v1.w);
    out->v2 = (float4)(wp_instance_to_world(m, object->v2.xyz), object->v2.w);
}

/* Vertex normals in the world: each by the inverse transpose, normalised. */
static inline void wp_instance_world_normals(__global const WpInstance* m, WpShadingNormals* n) {
    n->n0 = (float4)(normalize(wp_instance_normal_to_world(m, n->n0.xyz)), 0.0f);
    n->n1 = (float4)(normalize(wp_instance_normal_to_world(m, n->n1.xyz)), 0.0f);
    n->n2 = (float4)(normalize(wp_instance_normal_to_world(m, n->n2.xyz)), 0.0f);
}

#endif /* WP_INSTANCE_H */
