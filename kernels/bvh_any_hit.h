/* Any hit through the hierarchy (WP_USE_BVH): whether anything lies on a ray
 * segment, the question of every shadow ray.
 *
 * wp_bvh_trace answers it too, but carries the closest hit's bookkeeping:
 * entry distances on the stack, the test of each popped child against the
 * bound, the leaf's lanes looked at one by one. None of that can change an
 * any-hit answer: the bound is the segment's end throughout (the query ends
 * at its first hit), so every child pushed stays in range and a lane the
 * four-lane leaf test accepts is a hit as it stands. So here:
 *   - the stack holds the children alone (number and count), no distances;
 *   - a node's hit children are pushed in node order, unsorted, without a
 *     branch per child (nearest first was measured slower: most shadow
 *     segments are not blocked at all and visit every node they cross
 *     whatever the order);
 *   - a leaf of triangles answers as soon as one of its groups of four has a
 *     lane hit (wp_leaf_triangles_occluded);
 *   - the pushed children's first cache lines are prefetched: at 10^6
 *     triangles the traversal waits mostly on loads of nodes and triangles
 *     that miss the caches, and a pushed child is popped only after its
 *     siblings' subtrees, time enough for its lines to arrive.
 * docs/performance.md ("Any-hit traversal") has the measurements, and what
 * did not help.
 *
 * The answer is the same as wp_bvh_trace's with any_hit: the same box tests
 * against the same bound, the same leaf tests, so the same primitives are
 * found (maybe another one first, which an any-hit query cannot tell). */
#ifndef WP_BVH_ANY_HIT_H
#define WP_BVH_ANY_HIT_H

#include "bvh.h"

/* A hint that the 64-byte line at `address` is wanted soon. OpenCL's own
 * prefetch() compiles to nothing on PoCL 3.1 (no prefetch instruction in the
 * kernel's code), Clang's builtin to the CPU's prefetch instruction. Only
 * where the kernel is compiled for a CPU: for other targets the builtin
 * becomes an llvm.prefetch call that some cannot run (Oclgrind, which
 * compiles for SPIR, stops on it as an undefined function); there nothing. */
#if defined(__clang__) && (defined(__x86_64__) || defined(__aarch64__))
#define WP_PREFETCH_LINE(address) __builtin_prefetch((__global const char*)(address))
#else
#define WP_PREFETCH_LINE(address) ((void)(address))
#endif

/* Pushes the children of node n whose boxes the ray meets at 0 <= t <= t_max,
 * in node order. Every child is written at the top and kept only if hit:
 * straight-line code, four stores (a missed child's write lands one past the
 * top, which the stack has room for). Then each kept child's first lines are
 * prefetched: a node's two, or a leaf's first three (its first four
 * triangles); a leaf of other primitives is left alone. */
static inline void wp_bvh_push_hit_children(const WpSceneView* scene, __global const WpBvhNode* n,
                                            const WpBoxRay* ray, float t_max, wp_uint* children,
                                            wp_uint* counts, int* top) {
    float4 enter;
    int4 hit = wp_hit_child_boxes(n, ray, t_max, &enter);
    int first = *top, at = first;
    children[at] = n->child[0];
    counts[at] = n->count[0];
    at -= hit.s0;
    children[at] = n->child[1];
    counts[at] = n->count[1];
    at -= hit.s1;
    children[at] = n->child[2];
    counts[at] = n->count[2];
    at -= hit.s2;
    children[at] = n->child[3];
    counts[at] = n->count[3];
    at -= hit.s3;
    *top = at;
    for (int i = first; i < at; ++i) {
        if (counts[i] == 0u) {
            __global const char* node = (__global const char*)&scene->bvh_nodes[children[i]];
            WP_PREFETCH_LINE(node);
            WP_PREFETCH_LINE(node + 64);
        } else if (children[i] + counts[i] <= scene->triangle_count) {
            __global const char* leaf = (__global const char*)&scene->triangles[children[i]];
            WP_PREFETCH_LINE(leaf);
            WP_PREFETCH_LINE(leaf + 64);
            WP_PREFETCH_LINE(leaf + 128);
        }
    }
}

/* One any-hit query under way: the ray, its stack of children still to
 * visit, and the child it visits next. A work-item may hold several and step
 * them in turn (wp_bvh_occluded_stream), so that while one waits for a node
 * or leaf to arrive from memory the others' work goes on. */
typedef struct {
    WpShearedRay sheared;
    WpBoxRay box_ray;
    float3 origin, direction;
    float t_max;
    /* The host keeps the deepest path's pushes within WP_BVH_STACK_SIZE; one
     * more for a missed child's write past the top. */
    wp_uint children[WP_BVH_STACK_SIZE + 1], counts[WP_BVH_STACK_SIZE + 1];
    int top;
    wp_uint child, count; /* the next to visit */
    int running;          /* 0 once answered */
    int blocked;          /* the answer */
} WpAnyHitWalk;

static inline void wp_any_hit_walk_start(WpAnyHitWalk* walk, float3 origin, float3 direction,
                                         float t_max) {
    walk->sheared = wp_shear_ray(origin, direction);
    walk->box_ray = wp_box_ray(origin, direction);
    walk->origin = origin;
    walk->direction = direction;
    walk->t_max = t_max;
    walk->top = 0;
    walk->child = 0u; /* the root */
    walk->count = 0u;
    walk->running = 1;
    walk->blocked = 0;
}

/* Visits the walk's next child (pushes a node's hit children, or tests a
 * leaf) and takes the one after it off the stack; stops the walk at a hit or
 * once the stack is empty. */
static inline void wp_any_hit_walk_step(const WpSceneView* scene, WpAnyHitWalk* walk) {
    wp_uint child = walk->child, count = walk->count;
    float t_max = walk->t_max;
    int hit = 0;
    if (count == 0u) {
        wp_bvh_push_hit_children(scene, &scene->bvh_nodes[child], &walk->box_ray, t_max,
                                 walk->children, walk->counts, &walk->top);
    } else if (child + count <= scene->triangle_count) {
        hit = wp_leaf_triangles_occluded(scene->triangles, child, count, &walk->sheared, t_max);
    } else {
        for (wp_uint k = 0; k < count && !hit; ++k) {
            wp_uint primitive = child + k;
            float t;
#if WP_TRACE_INSTANCES
            /* Past the plain primitives: an instance, traversed in its
             * object space (instance_trace.h). */
            wp_uint plain = scene->triangle_count + scene->sphere_count;
            if (primitive >= plain) {
                hit = wp_instance_trace(scene, primitive - plain, walk->origin, walk->direction,
                                        t_max, 1, &t) != WP_NO_HIT;
                continue;
            }
#endif
            hit = wp_intersect_primitive(scene, &walk->sheared, walk->origin, walk->direction,
                                         primitive, t_max, &t);
        }
    }
    if (hit || walk->top == 0) {
        walk->blocked = hit;
        walk->running = 0;
        return;
    }
    --walk->top;
    walk->child = walk->children[walk->top];
    walk->count = walk->counts[walk->top];
}

/* 1 if a primitive lies on origin + t direction, 0 < t < t_max. */
static inline int wp_bvh_occluded(const WpSceneView* scene, float3 origin, float3 direction,
                                  float t_max) {
    WpAnyHitWalk walk;
    wp_any_hit_walk_start(&walk, origin, direction, t_max);
    while (walk.running)
        wp_any_hit_walk_step(scene, &walk);
    return walk.blocked;
}

/* The queries of `rays` walks at once (started, or with running 0 for none),
 * stepped in turn, one node or leaf each, until all are answered: the
 * traversal of one ray waits on memory one load after another, and stepping
 * another ray in between gives each load the other's work to hide behind. */
static inline void wp_bvh_occluded_stream(const WpSceneView* scene, WpAnyHitWalk* walks, int rays) {
    for (int running = 1; running;) {
        running = 0;
        for (int r = 0; r < rays; ++r) {
            if (walks[r].running) {
                wp_any_hit_walk_step(scene, &walks[r]);
                running |= walks[r].running;
            }
        }
    }
}

#endif /* WP_BVH_ANY_HIT_H */
