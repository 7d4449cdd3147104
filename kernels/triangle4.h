/* A hierarchy leaf's triangles, four at a time: triangle.h's watertight test
 * written on float4s, one triangle a lane, so that one ray tests four
 * triangles with SIMD instructions (the hierarchy's traversal is not
 * vectorised across work-items, so these are its only SIMD).
 *
 * The hits are bit-identical to testing the triangles one at a time, in
 * order, with wp_triangle_test and a shrinking bound (the loop this replaces):
 * each lane runs the same operations on the same operands (IEEE float
 * arithmetic gives the same result in a vector lane as in a scalar; no FMA
 * contraction, wp_shared.h), and every lane is tested against the bound the
 * leaf was entered with. Only the range test depends on the bound, and it can
 * only fail as the bound shrinks (wp_triangle_in_range), so the lanes that
 * pass are the candidates: walking them in order and testing each one's range
 * again against the running bound accepts exactly the triangles the scalar
 * loop accepts, with the same t (the same T / det) and the same outcome of
 * exact ties (where t rounds so that a later triangle at the same t still
 * passes, the later one, as in the loop).
 */
#ifndef WP_TRIANGLE4_H
#define WP_TRIANGLE4_H

#include "triangle.h"

/* Component `axis` of four points' (x, y, z): the ray's axis permutation is
 * the same in every lane, so this selects whole vectors. */
static inline float4 wp_axis4(float4 x, float4 y, float4 z, int axis) {
    return axis == 0 ? x : (axis == 1 ? y : z);
}

static inline float4 wp_max4(float4 a, float4 b) {
    return select(b, a, a > b); /* wp_max in every lane: a > b ? a : b */
}
static inline float4 wp_min4(float4 a, float4 b) {
    return select(b, a, a < b); /* wp_min: a < b ? a : b */
}

/* wp_triangle_test on four triangles, lane i the triangle with corners
 * (p0x.si, p0y.si, p0z.si) and so on: sets *T and *det to the lanes' scaled
 * distances and edge sums and returns the lanes (-1, else 0) among `lanes`
 * that the test accepts with bound t_max.
 *
 * The sliver guard can only reject, so it is computed only where some lane
 * of `lanes` has passed the edge and range tests: most groups a ray reaches
 * have none, and the guard (a dependent chain of 18 maxima) was the larger
 * part of the test. The lanes' answers are the same as testing all three. */
static inline int4 wp_triangle4_test(const WpShearedRay* ray, float4 p0x, float4 p0y, float4 p0z,
                                     float4 p1x, float4 p1y, float4 p1z, float4 p2x, float4 p2y,
                                     float4 p2z, float t_max, int4 lanes, float4* T_out,
                                     float4* det_out) {
    int kx = ray->kx, ky = ray->ky, kz = ray->kz;
    float4 az = wp_axis4(p0x, p0y, p0z, kz) - ray->oz;
    float4 bz = wp_axis4(p1x, p1y, p1z, kz) - ray->oz;
    float4 cz = wp_axis4(p2x, p2y, p2z, kz) - ray->oz;
    float4 a_x = wp_axis4(p0x, p0y, p0z, kx) - ray->ox;
    float4 a_y = wp_axis4(p0x, p0y, p0z, ky) - ray->oy;
    float4 b_x = wp_axis4(p1x, p1y, p1z, kx) - ray->ox;
    float4 b_y = wp_axis4(p1x, p1y, p1z, ky) - ray->oy;
    float4 c_x = wp_axis4(p2x, p2y, p2z, kx) - ray->ox;
    float4 c_y = wp_axis4(p2x, p2y, p2z, ky) - ray->oy;
    float4 ax = a_x - ray->sx * az;
    float4 ay = a_y - ray->sy * az;
    float4 bx = b_x - ray->sx * bz;
    float4 by = b_y - ray->sy * bz;
    float4 cx = c_x - ray->sx * cz;
    float4 cy = c_y - ray->sy * cz;

    float4 u = cx * by - cy * bx; /* edge p1-p2 */
    float4 v = ax * cy - ay * cx; /* edge p2-p0 */
    float4 w = bx * ay - by * ax; /* edge p0-p1 */
    int4 negative = (u < 0.0f) | (v < 0.0f) | (w < 0.0f);
    int4 positive = (u > 0.0f) | (v > 0.0f) | (w > 0.0f);
    int4 inside = ~(negative & positive);
    float4 det = u + v + w;

    float4 T = u * (ray->sz * az) + v * (ray->sz * bz) + w * (ray->sz * cz);
    float4 bound = t_max * det;
    int4 in_range = select((det != 0.0f) & ~((T >= 0.0f) | (T <= bound)),
                           ~((T <= 0.0f) | (T >= bound)), det > 0.0f);
    *T_out = T;
    *det_out = det;
    int4 candidates = lanes & inside & in_range;
    if (!any(candidates))
        return (int4)(0);

    /* The sliver guard (triangle.h), the same maxima and minima. */
    float4 m = wp_max4(a_x, -a_x);
    m = wp_max4(wp_max4(m, a_y), -a_y);
    m = wp_max4(wp_max4(m, az), -az);
    m = wp_max4(wp_max4(m, b_x), -b_x);
    m = wp_max4(wp_max4(m, b_y), -b_y);
    m = wp_max4(wp_max4(m, bz), -bz);
    m = wp_max4(wp_max4(m, c_x), -c_x);
    m = wp_max4(wp_max4(m, c_y), -c_y);
    m = wp_max4(wp_max4(m, cz), -cz);
    float4 slack = WP_SLIVER_GUARD_RELATIVE * m;
    float4 low_x = wp_min4(wp_min4(ax, bx), cx);
    float4 high_x = wp_max4(wp_max4(ax, bx), cx);
    float4 low_y = wp_min4(wp_min4(ay, by), cy);
    float4 high_y = wp_max4(wp_max4(ay, by), cy);
    int4 in_box = ~((low_x > slack) | (high_x < -slack) | (low_y > slack) | (high_y < -slack));
    return candidates & in_box;
}

/* wp_triangle4_test on the four triangles group .. group + 3 of a leaf whose
 * last triangle is `last`: lanes past the leaf's end test its last triangle
 * again and are dropped from the result (0 in their lane). Always inlined:
 * with two callers in a kernel (the closest-hit and any-hit walks) PoCL kept
 * it out of line, and each call passed T and det back through memory. */
static inline WP_ALWAYS_INLINE int4 wp_triangle4_group_test(__global const WpTriangle* triangles,
                                                            wp_uint group, wp_uint last,
                                                            const WpShearedRay* ray, float t_max,
                                                            float4* T, float4* det) {
    __global const WpTriangle* t0 = &triangles[group];
    __global const WpTriangle* t1 = &triangles[min(group + 1u, last)];
    __global const WpTriangle* t2 = &triangles[min(group + 2u, last)];
    __global const WpTriangle* t3 = &triangles[min(group + 3u, last)];
    float4 a0 = t0->v0, a1 = t1->v0, a2 = t2->v0, a3 = t3->v0;
    float4 b0 = t0->v1, b1 = t1->v1, b2 = t2->v1, b3 = t3->v1;
    float4 c0 = t0->v2, c1 = t1->v2, c2 = t2->v2, c3 = t3->v2;
    wp_uint lanes = min(last - group + 1u, 4u);
    return wp_triangle4_test(ray, (float4)(a0.x, a1.x, a2.x, a3.x),
                             (float4)(a0.y, a1.y, a2.y, a3.y), (float4)(a0.z, a1.z, a2.z, a3.z),
                             (float4)(b0.x, b1.x, b2.x, b3.x), (float4)(b0.y, b1.y, b2.y, b3.y),
                             (float4)(b0.z, b1.z, b2.z, b3.z), (float4)(c0.x, c1.x, c2.x, c3.x),
                             (float4)(c0.y, c1.y, c2.y, c3.y), (float4)(c0.z, c1.z, c2.z, c3.z),
                             t_max, (int4)(0, 1, 2, 3) < (int4)((int)lanes), T, det);
}

/* The triangles first .. first + count - 1 of `triangles` hit by the ray at
 * 0 < t < *closest: returns the closest one (with any_hit, the first one in
 * order) and lowers *closest to its t, or returns WP_NO_HIT and leaves
 * *closest as it is. */
static inline wp_uint wp_leaf_triangles(__global const WpTriangle* triangles, wp_uint first,
                                        wp_uint count, const WpShearedRay* ray, int any_hit,
                                        float* closest) {
    wp_uint hit = WP_NO_HIT;
    wp_uint last = first + count - 1u;
    for (wp_uint group = first; group <= last; group += 4u) {
        float4 T, det;
        int4 found = wp_triangle4_group_test(triangles, group, last, ray, *closest, &T, &det);
        if (!any(found))
            continue;
        float Ts[4], dets[4];
        int founds[4];
        vstore4(T, 0, Ts);
        vstore4(det, 0, dets);
        vstore4(found, 0, founds);
        for (int k = 0; k < 4; ++k) {
            /* The scalar loop's test of this triangle against the bound as it
             * stands by now: a candidate that is no longer in range fails. */
            if (founds[k] && wp_triangle_in_range(Ts[k], dets[k], *closest)) {
                *closest = Ts[k] / dets[k];
                hit = group + (wp_uint)k;
                if (any_hit)
                    return hit;
            }
        }
    }
    return hit;
}

/* 1 if any of the triangles first .. first + count - 1 lies on the ray at
 * 0 < t < t_max. The bound never shrinks here, so a lane that the four-lane
 * test accepts is a hit as it stands: no lane is looked at on its own, no t
 * is divided out. The same answer as wp_leaf_triangles with any_hit. */
static inline int wp_leaf_triangles_occluded(__global const WpTriangle* triangles, wp_uint first,
                                             wp_uint count, const WpShearedRay* ray, float t_max) {
    wp_uint last = first + count - 1u;
    for (wp_uint group = first; group <= last; group += 4u) {
        float4 T, det;
        if (any(wp_triangle4_group_test(triangles, group, last, ray, t_max, &T, &det)))
            return 1;
    }
    return 0;
}

#endif /* WP_TRIANGLE4_H */
