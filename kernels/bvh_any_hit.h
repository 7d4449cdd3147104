/* Any hit through the hierarchy (WP_USE_BVH): whether anything lies on a ray
 * segment, the question of every shadow ray.
 *
 * The closest hit's traversal (wp_bvh_trace) would answer it too, but carries
 * its bookkeeping: entry distances on the stack, the test of each popped
 * child against the bound, the leaf's lanes looked at one by one. None of that can change an
 * any-hit answer: the bound is the segment's end throughout (the query ends
 * at its first hit), so every child pushed stays in range and a lane the
 * four-lane leaf test accepts is a hit as it stands. So here:
 *   - the stack holds the children alone (number and count), no distances;
 *   - a node's hit children are pushed unsorted, without a branch per
 *     child, last child first, so that they are visited in node order
 *     (nearest first was measured slower: most shadow segments are not
 *     blocked at all and visit every node they cross whatever the order).
 *     Node order is the builder's tree order, the lower side of each split
 *     first (src/scene/bvh.cpp); a shadow ray toward a light above its origin
 *     (a ceiling light, the sky) meets that side first, so a blocked one
 *     finds its blocker after fewer nodes and leaves than in the opposite
 *     order, and the walk also moves forward through memory (children and
 *     leaves are stored in tree order). A ray toward a light below its
 *     origin meets the far side first, as rays toward lights above did with
 *     the opposite order (docs/performance.md, "Any hit: children visited in
 *     node order");
 *   - a leaf of triangles answers as soon as one of its groups of four has a
 *     lane hit (wp_leaf_triangles_occluded);
 *   - the pushed children's first cache lines are prefetched: at 10^6
 *     triangles the traversal waits mostly on loads of nodes and triangles
 *     that miss the caches, and a pushed child is popped only after its
 *     siblings' subtrees, time enough for its lines to arrive.
 * docs/performance.md ("Any-hit traversal") has the measurements, and what
 * did not help (two or four rays a work-item, their walks stepped in turn).
 *
 * Instances are walked the same way in their object space
 * (wp_instance_occluded). The answer is whether wp_bvh_trace finds a closest
 * hit before t_max: the same box tests, the same leaf tests. */
#ifndef WP_BVH_ANY_HIT_H
#define WP_BVH_ANY_HIT_H

#include "bvh.h"
#include "prefetch.h"

/* Pushes the children of node n (of `nodes`, whose leaves index `triangles`
 * up to triangle_end and other primitives past it) whose boxes the ray meets
 * at 0 <= t <= t_max, the last child first (so child 0 is on top, visited
 * first). Every child is written at the top and
 * kept only if hit: straight-line code, eight stores (a missed child's write
 * lands one past the top, which the stack has room for). Then each kept
 * child's first lines are prefetched: a node's four, or a leaf's first three
 * (its first four triangles); a leaf of other primitives is left alone. */
static inline void wp_bvh_push_hit_children(__global const WpBvhNode* nodes,
                                            __global const WpTriangle* triangles,
                                            wp_uint triangle_end, __global const WpBvhNode* n,
                                            const WpBoxRay* ray, float t_max, wp_uint* children,
                                            wp_uint* counts, int* top) {
    float8 enter;
    int8 hit = wp_hit_child_boxes(n, ray, t_max, &enter);
    int first = *top, at = first;
#define WP_PUSH_IF_HIT(i, lane)                                                                    \
    children[at] = n->child[i];                                                                    \
    counts[at] = n->count[i];                                                                      \
    at -= hit.lane;
    WP_PUSH_IF_HIT(7, s7)
    WP_PUSH_IF_HIT(6, s6)
    WP_PUSH_IF_HIT(5, s5)
    WP_PUSH_IF_HIT(4, s4)
    WP_PUSH_IF_HIT(3, s3)
    WP_PUSH_IF_HIT(2, s2)
    WP_PUSH_IF_HIT(1, s1)
    WP_PUSH_IF_HIT(0, s0)
#undef WP_PUSH_IF_HIT
    *top = at;
    for (int i = first; i < at; ++i) {
        if (counts[i] == 0u) {
            __global const char* node = (__global const char*)&nodes[children[i]];
            WP_PREFETCH_LINE(node);
            WP_PREFETCH_LINE(node + 64);
            WP_PREFETCH_LINE(node + 128);
            WP_PREFETCH_LINE(node + 192);
        } else if (children[i] + counts[i] <= triangle_end) {
            __global const char* leaf = (__global const char*)&triangles[children[i]];
            WP_PREFETCH_LINE(leaf);
            WP_PREFETCH_LINE(leaf + 64);
            WP_PREFETCH_LINE(leaf + 128);
        }
    }
}

/* Takes the next child off the stack into *child and *count; 0 when the
 * stack is empty (the walk is over). */
static inline int wp_bvh_pop_child(const wp_uint* children, const wp_uint* counts, int* top,
                                   wp_uint* child, wp_uint* count) {
    if (*top == 0)
        return 0;
    --*top;
    *child = children[*top];
    *count = counts[*top];
    return 1;
}

#if WP_TRACE_INSTANCES
/* 1 if a triangle of instance `instance` lies on origin + t direction
 * (world), 0 < t < t_max: the same walk through its group's hierarchy in
 * object space (instance_trace.h has the closest hit's), whose leaves are
 * all triangles. */
static inline int wp_instance_occluded(const WpSceneView* scene, wp_uint instance, float3 origin,
                                       float3 direction, float t_max) {
    __global const WpInstance* m = &scene->instances[instance];
    float3 o, d;
    wp_instance_object_ray(m, origin, direction, &o, &d);
    WpShearedRay sheared = wp_shear_ray(o, d);
    WpBoxRay box_ray = wp_box_ray(o, d);
    /* As wp_bvh_occluded's below; the host checks the groups' depths too. */
    wp_uint children[WP_BVH_STACK_SIZE + 1], counts[WP_BVH_STACK_SIZE + 1];
    int top = 0;
    wp_uint child = m->root, count = 0u;
    for (;;) {
        if (count == 0u) {
            wp_bvh_push_hit_children(scene->group_bvh_nodes, scene->group_triangles, 0xffffffffu,
                                     &scene->group_bvh_nodes[child], &box_ray, t_max, children,
                                     counts, &top);
        } else if (wp_leaf_triangles_occluded(scene->group_triangles, child, count, &sheared,
                                              t_max)) {
            return 1;
        }
        if (!wp_bvh_pop_child(children, counts, &top, &child, &count))
            return 0;
    }
}
#endif

/* 1 if a primitive lies on origin + t direction, 0 < t < t_max. */
static inline int wp_bvh_occluded(const WpSceneView* scene, float3 origin, float3 direction,
                                  float t_max) {
    WpShearedRay sheared = wp_shear_ray(origin, direction);
    WpBoxRay box_ray = wp_box_ray(origin, direction);
    /* The host keeps the deepest path's pushes within WP_BVH_STACK_SIZE; one
     * more for a missed child's write past the top. */
    wp_uint children[WP_BVH_STACK_SIZE + 1], counts[WP_BVH_STACK_SIZE + 1];
    int top = 0;
    wp_uint child = 0u, count = 0u; /* the root */
    for (;;) {
        if (count == 0u) {
            wp_bvh_push_hit_children(scene->bvh_nodes, scene->triangles, scene->triangle_count,
                                     &scene->bvh_nodes[child], &box_ray, t_max, children, counts,
                                     &top);
        } else if (child + count <= scene->triangle_count) {
            if (wp_leaf_triangles_occluded(scene->triangles, child, count, &sheared, t_max))
                return 1;
        } else {
            for (wp_uint k = 0; k < count; ++k) {
                wp_uint primitive = child + k;
                float t;
#if WP_TRACE_INSTANCES
                /* Past the plain primitives: an instance, traversed in its
                 * object space (instance_trace.h). */
                wp_uint plain = scene->triangle_count + scene->sphere_count;
                if (primitive >= plain) {
                    if (wp_instance_occluded(scene, primitive - plain, origin, direction, t_max))
                        return 1;
                    continue;
                }
#endif
                if (wp_intersect_primitive(scene, &sheared, origin, direction, primitive, t_max,
                                           &t))
                    return 1;
            }
        }
        if (!wp_bvh_pop_child(children, counts, &top, &child, &count))
            return 0;
    }
}

#endif /* WP_BVH_ANY_HIT_H */
