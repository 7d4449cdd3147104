/* dp/du, the derivative of the surface point along the first texture
 * coordinate: the direction an anisotropic BSDF's alpha_u runs along
 * (WP_HAS_ANISOTROPY; bsdf/frame.h orthogonalises it against the shading
 * normal). As Mitsuba 3.9.1 computes SurfaceInteraction::dp_du (measured with
 * its ray_intersect, tests/kernels/test_tangent.cpp), so that an anisotropic
 * highlight runs the way Mitsuba's does:
 *   - a triangle with texture coordinates: dp/du of the linear map from
 *     (u, v) to the triangle's points;
 *   - a triangle without them, parameterised by its barycentrics (b1, b2) as
 *     its textures are: v1 - v0;
 *   - a triangle whose texture coordinates are degenerate (collinear): the
 *     first tangent of wp_make_basis of its geometric normal, as Mitsuba
 *     falls back to coordinate_system(n);
 *   - a sphere, u = phi / 2 pi about its centre (phi from +x towards +y):
 *     2 pi (-y, x, 0) from the centre; 0 at the poles, where bsdf/frame.h
 *     falls back to wp_make_basis(n) as Mitsuba does.
 * Only the direction matters: the frame normalises it. */
#ifndef WP_TANGENT_H
#define WP_TANGENT_H

#include "sampling.h"
#include "stage.h"

static inline float3 wp_triangle_dp_du(const WpSceneView* scene, const WpTriangle* t,
                                       float3 normal) {
    float3 e1 = t->v1.xyz - t->v0.xyz, e2 = t->v2.xyz - t->v0.xyz;
    wp_uint uvs = wp_triangle_uvs(t);
    if (uvs == 0u)
        return e1;
    WpTriangleUvs c = scene->triangle_uvs[uvs - 1u];
    float du1 = c.u.y - c.u.x, dv1 = c.v.y - c.v.x;
    float du2 = c.u.z - c.u.x, dv2 = c.v.z - c.v.x;
    float det = du1 * dv2 - dv1 * du2;
    if (det == 0.0f || !isfinite(1.0f / det)) {
        float3 tangent, bitangent;
        wp_make_basis(normal, &tangent, &bitangent);
        return tangent;
    }
    /* Solving e1 = du1 dp/du + dv1 dp/dv, e2 = du2 dp/du + dv2 dp/dv. */
    return (dv2 * e1 - dv1 * e2) * (1.0f / det);
}

/* n: the unit direction from the sphere's centre. The factor 2 pi r, which
 * the frame normalises away, is left out. */
static inline float3 wp_sphere_dp_du(float3 n) {
    return (float3)(-n.y, n.x, 0.0f);
}

#endif /* WP_TANGENT_H */
