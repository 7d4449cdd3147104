/* Traversal of the bounding volume hierarchy (WP_USE_BVH): the closest hit,
 * or any hit, among the primitives on a ray segment.
 *
 * Depth first with a private stack over four-wide nodes: at a node all four
 * children's boxes are tested (independent scalar code, the bounds stored as
 * arrays of each coordinate), the children hit are pushed farthest first with
 * their entry distances, and the nearest is visited next; popped children
 * that start beyond the closest hit found since are skipped. Leaves test their primitives with the
 * same tests, limits and update rule as the loop over all primitives (traverse.h), so a ray finds
 * the same hit at the same t; only between primitives hit at exactly the same t (rays through a
 * shared edge) may the order decide which one is reported.
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

/* Narrows [*t_enter, *t_exit] to the slab lower < x < upper of one axis.
 * The comparisons are written so that a NaN (origin on the slab's plane, the
 * direction parallel to it) changes nothing. */
static inline void wp_clip_slab(float lower, float upper, float origin, float inverse,
                                float* t_enter, float* t_exit) {
    float near = (lower - origin) * inverse;
    float far = (upper - origin) * inverse;
    if (near > far) {
        float swap = near;
        near = far;
        far = swap;
    }
    far *= WP_BOX_EXIT_SCALE;
    *t_enter = near > *t_enter ? near : *t_enter;
    *t_exit = far < *t_exit ? far : *t_exit;
}

/* 1 if the ray meets child i's box at some 0 <= t <= t_max; *t_enter is
 * where it enters. */
static inline int wp_hit_child_box(__global const WpBvhNode* node, int i, const WpBoxRay* ray,
                                   float t_max, float* t_enter) {
    float enter = 0.0f, exit = t_max;
    wp_clip_slab(node->lower_x[i], node->upper_x[i], ray->origin.x, ray->inverse_direction.x,
                 &enter, &exit);
    wp_clip_slab(node->lower_y[i], node->upper_y[i], ray->origin.y, ray->inverse_direction.y,
                 &enter, &exit);
    wp_clip_slab(node->lower_z[i], node->upper_z[i], ray->origin.z, ray->inverse_direction.z,
                 &enter, &exit);
    *t_enter = enter;
    return enter <= exit;
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
    int base = *top;
    for (int i = 0; i < 4; ++i) {
        float enter;
        wp_uint count = n->count[i];
        if (count != WP_BVH_EMPTY && wp_hit_child_box(n, i, box_ray, closest, &enter)) {
            /* Insert, keeping this node's entries nearest on top. */
            int j = (*top)++;
            while (j > base && stack[j - 1].enter < enter) {
                stack[j] = stack[j - 1];
                --j;
            }
            stack[j].child = n->child[i];
            stack[j].count = count;
            stack[j].enter = enter;
        }
    }
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
                                   float t_max, int any_hit, float* t_hit) {
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
        } else {
            for (wp_uint k = 0; k < current.count; ++k) {
                wp_uint primitive = current.child + k;
                float t;
#if WP_TRACE_INSTANCES
                /* Past the plain primitives: an instance, traversed in its
                 * object space (instance.h). */
                wp_uint plain = scene->triangle_count + scene->sphere_count;
                if (primitive >= plain) {
                    wp_uint instance_hit = wp_instance_trace(scene, primitive - plain, origin,
                                                             direction, closest, any_hit, &t);
                    if (instance_hit != WP_NO_HIT) {
                        closest = t;
                        hit = instance_hit;
                        if (any_hit) {
                            *t_hit = closest;
                            return hit;
                        }
                    }
                    continue;
                }
#endif
                if (wp_intersect_primitive(scene, &sheared, origin, direction, primitive, closest,
                                           &t)) {
                    closest = t;
                    hit = primitive;
                    if (any_hit) {
                        *t_hit = closest;
                        return hit;
                    }
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
