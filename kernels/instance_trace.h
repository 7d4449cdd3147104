/* The traversal of one instance's group (instance.h has the model):
 * included by bvh.h after its traversal helpers, which it shares. */
#ifndef WP_INSTANCE_TRACE_H
#define WP_INSTANCE_TRACE_H

#include "instance.h"

/* The triangles of instance `instance` hit by origin + t direction (world),
 * 0 < t < t_max: the closest (bvh_any_hit.h has the any-hit query). Returns the
 * hit's primitive number (wp_shared.h, WpInstance) or WP_NO_HIT, and its t in
 * *t_hit. */
static inline wp_uint wp_instance_trace(const WpSceneView* scene, wp_uint instance, float3 origin,
                                        float3 direction, float t_max, float* t_hit) {
    __global const WpInstance* m = &scene->instances[instance];
    float3 o, d;
    wp_instance_object_ray(m, origin, direction, &o, &d);
    wp_uint hit = WP_NO_HIT;
    float closest = t_max;
    WpShearedRay sheared = wp_shear_ray(o, d);
    WpBoxRay box_ray = wp_box_ray(o, d);
    WpBvhEntry stack[WP_BVH_STACK_SIZE];
    int top = 0;
    WpBvhEntry current;
    current.child = m->root;
    current.count = 0u;
    current.enter = 0.0f;
    for (;;) {
        if (current.count == 0u) {
            wp_bvh_push_children(&scene->group_bvh_nodes[current.child], &box_ray, closest, stack,
                                 &top);
        } else {
            wp_uint found = wp_leaf_triangles(scene->group_triangles, current.child, current.count,
                                              &sheared, 0, &closest);
            if (found != WP_NO_HIT)
                hit = found;
        }
        if (!wp_bvh_pop(stack, &top, closest, &current))
            break;
    }
    *t_hit = closest;
    if (hit == WP_NO_HIT)
        return WP_NO_HIT;
    return scene->triangle_count + scene->sphere_count + m->first_primitive +
           (hit - m->first_triangle);
}

#endif /* WP_INSTANCE_TRACE_H */
