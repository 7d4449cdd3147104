/* Traversal of the bounding volume hierarchy (WP_USE_BVH): the closest hit,
 * or any hit, among the primitives on a ray segment.
 *
 * Depth first with a private stack: at an inner node both children's boxes
 * are tested, the nearer one is visited next and the farther one pushed with
 * its entry distance, and popped nodes that start beyond the closest hit
 * found since are skipped. Leaves test their primitives with the same tests,
 * limits and update rule as the loop over all primitives (traverse.h), so a
 * ray finds the same hit at the same t; only between primitives hit at
 * exactly the same t (rays through a shared edge) may the order decide which
 * one is reported.
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
#define WP_BVH_STACK_SIZE 64

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

/* 1 if the ray meets the node's box at some 0 <= t <= t_max; *t_enter is
 * where it enters. */
static inline int wp_hit_box(__global const WpBvhNode* node, const WpBoxRay* ray, float t_max,
                             float* t_enter) {
    float enter = 0.0f, exit = t_max;
    wp_clip_slab(node->lower_x, node->upper_x, ray->origin.x, ray->inverse_direction.x, &enter,
                 &exit);
    wp_clip_slab(node->lower_y, node->upper_y, ray->origin.y, ray->inverse_direction.y, &enter,
                 &exit);
    wp_clip_slab(node->lower_z, node->upper_z, ray->origin.z, ray->inverse_direction.z, &enter,
                 &exit);
    *t_enter = enter;
    return enter <= exit;
}

static inline wp_uint wp_bvh_trace(const WpSceneView* scene, float3 origin, float3 direction,
                                   float t_max, int any_hit, float* t_hit) {
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
    WpShearedRay sheared = wp_shear_ray(origin, direction);
    WpBoxRay box_ray = wp_box_ray(origin, direction);
    wp_uint stack_node[WP_BVH_STACK_SIZE];
    float stack_enter[WP_BVH_STACK_SIZE];
    int top = 0;
    wp_uint node = 0;
    float enter;
    int active = wp_hit_box(&scene->bvh_nodes[0], &box_ray, closest, &enter);
    while (active) {
        __global const WpBvhNode* n = &scene->bvh_nodes[node];
        if (n->count > 0u) {
            for (wp_uint k = 0; k < n->count; ++k) {
                wp_uint primitive = n->offset + k;
                float t;
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
        } else {
            wp_uint first = node + 1u, second = n->offset;
            float enter_first, enter_second;
            int hit_first = wp_hit_box(&scene->bvh_nodes[first], &box_ray, closest, &enter_first);
            int hit_second =
                wp_hit_box(&scene->bvh_nodes[second], &box_ray, closest, &enter_second);
            if (hit_first && hit_second) {
                int second_nearer = enter_second < enter_first;
                stack_node[top] = second_nearer ? first : second;
                stack_enter[top] = second_nearer ? enter_first : enter_second;
                ++top; /* at most WP_BVH_MAX_DEPTH entries: the host builds no deeper */
                node = second_nearer ? second : first;
                continue;
            }
            if (hit_first || hit_second) {
                node = hit_first ? first : second;
                continue;
            }
        }
        /* Next: the nearest pushed node that may still hold a closer hit. */
        active = 0;
        while (top > 0) {
            --top;
            if (stack_enter[top] <= closest) {
                node = stack_node[top];
                active = 1;
                break;
            }
        }
    }
    *t_hit = closest;
    return hit;
}

#endif /* WP_BVH_H */
