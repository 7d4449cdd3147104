/* Traversal of the bounding volume hierarchy (WP_USE_BVH): the closest hit
 * among the primitives on a ray segment.
 *
 * Depth first with a private stack over eight-wide nodes: at a node all eight
 * children's boxes are tested at once (float8 code, one child a lane, from
 * the bounds stored as arrays of each coordinate), the children hit are
 * pushed farthest first with their entry distances, and the nearest is
 * visited next; popped children that start beyond the closest hit found since
 * are skipped. (Any-hit queries, the shadow rays' and those inside instances,
 * take a traversal of their own: bvh_any_hit.h.)
 * Leaves of triangles are tested four at a time (triangle4.h), other leaves
 * one primitive at a time; both give the hits of the loop over all primitives
 * (traverse.h): the same tests, limits and update rule, so a ray finds the
 * same hit at the same t; only between primitives hit at exactly the same t
 * (rays through a shared edge) may the order decide which one is reported.
 *
 * The box test is conservative: a slab test whose exit distance is enlarged
 * by 1 + 2 gamma(3) for its own rounding (pbrt-v4, after Ize 2013), with a
 * coordinate of the direction that is 0 imposing no limit rather than a NaN
 * one, on boxes the host widened by the intersection tests' own tolerance.
 * So no ray that the watertight triangle test would let hit a triangle is
 * culled on the way to it, and closed meshes stay closed through the
 * hierarchy.
 */
#ifndef WP_BVH_H
#define WP_BVH_H

#include "primitive.h"
#include "sphere.h"
#include "stage.h"
#include "triangle.h"
#include "triangle4.h"

/* 1 + 2 gamma(3), gamma(n) = n eps / (1 - n eps), eps = 2^-24. */
#define WP_BOX_EXIT_SCALE 1.0000007152557373f

typedef struct {
    float3 origin;
    float3 inverse_direction; /* components may be infinite */
} WpBoxRay;

static inline WpBoxRay wp_box_ray(float3 origin, float3 direction) {
    WpBoxRay r;
    r.origin = origin;
    r.inverse_direction = (float3)(1.0f / direction.x, 1.0f / direction.y, 1.0f / direction.z);
    return r;
}

/* Narrows each lane's [*t_enter, *t_exit] to the slab lower < x < upper of
 * one axis, for the eight children of a node at once. The comparisons are
 * written so that a NaN (origin on the slab's plane, the direction parallel
 * to it) changes nothing. */
static inline void wp_clip_slab8(float8 lower, float8 upper, float origin, float inverse,
                                 float8* t_enter, float8* t_exit) {
    float8 near = (lower - origin) * inverse;
    float8 far = (upper - origin) * inverse;
    int8 swap = near > far;
    float8 entry = select(near, far, swap);
    float8 leave = select(far, near, swap) * WP_BOX_EXIT_SCALE;
    *t_enter = select(*t_enter, entry, entry > *t_enter);
    *t_exit = select(*t_exit, leave, leave < *t_exit);
}

/* The eight children of node n whose boxes the ray meets at some
 * 0 <= t <= t_max (-1 in their lane, else 0; never an empty child), and where
 * it enters each. Straight-line code on float8s, one child a lane, with no
 * branch per child: eight box tests for the instructions of one (one AVX
 * register a coordinate where the CPU has them). */
static inline int8 wp_hit_child_boxes(__global const WpBvhNode* n, const WpBoxRay* ray, float t_max,
                                      float8* t_enter) {
    float8 enter = (float8)(0.0f), exit = (float8)(t_max);
    wp_clip_slab8(vload8(0, n->lower_x), vload8(0, n->upper_x), ray->origin.x,
                  ray->inverse_direction.x, &enter, &exit);
    wp_clip_slab8(vload8(0, n->lower_y), vload8(0, n->upper_y), ray->origin.y,
                  ray->inverse_direction.y, &enter, &exit);
    wp_clip_slab8(vload8(0, n->lower_z), vload8(0, n->upper_z), ray->origin.z,
                  ray->inverse_direction.z, &enter, &exit);
    *t_enter = enter;
    return (enter <= exit) & (vload8(0, n->count) != (uint8)(WP_BVH_EMPTY));
}

/* A child waiting on the stack: a node (count 0) or a leaf, and where the ray
 * enters its box. */
typedef struct {
    wp_uint child;
    wp_uint count;
    float enter;
} WpBvhEntry;

/* Pushes the children of node n that the ray meets before `closest`,
 * farthest first, so that the nearest is on top. */
static inline void wp_bvh_push_children(__global const WpBvhNode* n, const WpBoxRay* box_ray,
                                        float closest, WpBvhEntry* stack, int* top) {
    float8 enter8;
    int8 hit8 = wp_hit_child_boxes(n, box_ray, closest, &enter8);
    /* The hit lanes as the bits of one mask (lane i, bit i), so that the loop
     * below runs once per hit child, in lane order, instead of testing all
     * eight lanes with a branch each. */
    int8 bits = hit8 & (int8)(1, 2, 4, 8, 16, 32, 64, 128);
    int4 bits4 = bits.lo | bits.hi;
    int2 bits2 = bits4.lo | bits4.hi;
    wp_uint mask = (wp_uint)(bits2.x | bits2.y);
    if (mask == 0u)
        return;
    float enters[WP_BVH_WIDTH];
    vstore8(enter8, 0, enters);
    int base = *top;
    do {
        int i = 31 - (int)clz(mask & (0u - mask)); /* the lowest hit lane */
        mask &= mask - 1u;
        float enter = enters[i];
        /* Insert, keeping this node's entries nearest on top. */
        int j = (*top)++;
        while (j > base && stack[j - 1].enter < enter) {
            stack[j] = stack[j - 1];
            --j;
        }
        stack[j].child = n->child[i];
        stack[j].count = n->count[i];
        stack[j].enter = enter;
    } while (mask != 0u);
}

/* Next: the nearest pushed child that may still hold a closer hit, into
 * *current; 0 when none is left. */
static inline int wp_bvh_pop(WpBvhEntry* stack, int* top, float closest, WpBvhEntry* current) {
    while (*top > 0) {
        --*top;
        if (stack[*top].enter <= closest) {
            *current = stack[*top];
            return 1;
        }
    }
    return 0;
}

#if WP_TRACE_INSTANCES
#include "instance_trace.h"
#endif

static inline wp_uint wp_bvh_trace(const WpSceneView* scene, float3 origin, float3 direction,
                                   float t_max, float* t_hit) {
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
    WpShearedRay sheared = wp_shear_ray(origin, direction);
    WpBoxRay box_ray = wp_box_ray(origin, direction);
    /* Every node pushes its hit children, farthest first, so the nearest is
     * on top; the host keeps the deepest path's pushes within the stack. */
    WpBvhEntry stack[WP_BVH_STACK_SIZE];
    int top = 0;
    WpBvhEntry current;
    current.child = 0u; /* the root */
    current.count = 0u;
    current.enter = 0.0f;
    for (;;) {
        if (current.count == 0u) {
            wp_bvh_push_children(&scene->bvh_nodes[current.child], &box_ray, closest, stack, &top);
        } else if (current.child + current.count <= scene->triangle_count) {
            /* A leaf of triangles: four at a time (triangle4.h). */
            wp_uint found = wp_leaf_triangles(scene->triangles, current.child, current.count,
                                              &sheared, 0, &closest);
            if (found != WP_NO_HIT)
                hit = found;
        } else {
            for (wp_uint k = 0; k < current.count; ++k) {
                wp_uint primitive = current.child + k;
                float t;
#if WP_TRACE_INSTANCES
                /* Past the plain primitives: an instance, traversed in its
                 * object space (instance.h). */
                wp_uint plain = scene->triangle_count + scene->sphere_count;
                if (primitive >= plain) {
                    wp_uint instance_hit =
                        wp_instance_trace(scene, primitive - plain, origin, direction, closest, &t);
                    if (instance_hit != WP_NO_HIT) {
                        closest = t;
                        hit = instance_hit;
                    }
                    continue;
                }
#endif
                if (wp_intersect_primitive(scene, &sheared, origin, direction, primitive, closest,
                                           &t)) {
                    closest = t;
                    hit = primitive;
                }
            }
        }
        if (!wp_bvh_pop(stack, &top, closest, &current))
            break;
    }
    *t_hit = closest;
    return hit;
}

#endif /* WP_BVH_H */
