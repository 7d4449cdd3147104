/* Next-event estimation through planar mirrors (WP_MIRROR_NEE).
 *
 * No shadow ray finds a light by way of a mirror, so without this the light
 * a mirror throws onto diffuse surfaces (a caustic) is found only by paths
 * that bounce diffuse -> mirror -> light, a few bright samples. For a perfect
 * planar mirror the light's mirror image is exact: from a diffuse point x,
 * sample a point y on the lights (by area, as lights.h does), reflect it in
 * the mirror's plane (y'), and the segment x -> y' meets the plane at the
 * mirror point m, which must lie inside the mirror's outline (one of its
 * triangles). If both legs, x -> m and m -> y, are unblocked the light
 * arrives with
 *     f(x) Le R(m) cos_x cos_y / |x - y'|^2 / p(y),
 * cos_y taken against the reflected direction (the image of the light is
 * seen at distance |x - y'| = |x - m| + |m - y|).
 *
 * The path diffuse x -> mirror -> light found by sampling the BSDF at x
 * finds the same light, so the two strategies are combined by multiple
 * importance sampling (the power heuristic): each weighs its sample by its
 * own solid-angle density at x against the other's,
 *     p_bsdf(x, wi)   the diffuse BSDF's density of the direction wi,
 *     p_mirror(wi) = |x - y'|^2 / (cos_y * light area * mirror count),
 * and the weights of the two sum to 1 for every path, so nothing is counted
 * twice or lost. The mirrored strategy samples its mirror uniformly among the
 * scene's planar mirrors (WpMirrorGroup, src/render/planar_mirrors.hpp: the
 * host groups coplanar mirror triangles without vertex normals). Paths with
 * two or more mirror bounces, or by way of a curved mirror, keep weight 1.
 *
 * The shading side (kernels/shade.cl) keeps the last diffuse vertex and its
 * BSDF density in mirror_vertex, and WP_PATH_PLANAR_MIRROR in path_flags
 * while the path's last two vertices were diffuse, then a planar mirror;
 * shade pushes the two-leg ray onto the mirror queue (shadow_queue from
 * pool_size on, its length in counters[WP_COUNTER_MIRROR_SHADOW_RAYS]),
 * which the kernel mirror_shadow (kernels/shadow.cl) tests after the shadow
 * stage.
 *
 * The light point reuses the numbers of the bounce's own next-event
 * estimation (the two estimates are each unbiased, so their sum is); the
 * mirror is picked by stretching the light-pick number.
 *
 * Compiled only with WP_MIRROR_NEE=1 (the host's --mirror-nee, default on),
 * in scenes with planar mirrors and lights (WP_HAS_PLANAR_MIRRORS) and
 * next-event estimation; left undefined it is off, the original estimator.
 */
#ifndef WP_MIRROR_LIGHT_H
#define WP_MIRROR_LIGHT_H

#include "bsdf.h"
#include "lights.h"
#include "path_type.h"
#include "primitive.h"
#include "scene_features.h"

#ifndef WP_MIRROR_NEE
#define WP_MIRROR_NEE 0
#endif
#if !(WP_HAS_PLANAR_MIRRORS && WP_HAS_LIGHTS && WP_USE_NEE && WP_HAS_TRIANGLES)
#undef WP_MIRROR_NEE
#define WP_MIRROR_NEE 0
#endif

/* The power heuristic's weight of the strategy of density `own` against
 * `other` (0 when its own density is 0, 1 when the other's is). */
static inline float wp_mis_power(float own, float other) {
    if (!(own > 0.0f))
        return 0.0f;
    float r = other / own;
    return 1.0f / (1.0f + r * r);
}

/* Whether the point p of t's plane lies inside t or on its edge. */
static inline int wp_mirror_triangle_holds(WpTriangle t, float3 p) {
    float3 v0 = t.v0.xyz, v1 = t.v1.xyz, v2 = t.v2.xyz;
    float3 nt = cross(v1 - v0, v2 - v0);
    return dot(cross(v1 - v0, p - v0), nt) >= 0.0f && dot(cross(v2 - v1, p - v1), nt) >= 0.0f &&
           dot(cross(v0 - v2, p - v2), nt) >= 0.0f;
}

/* The mirror point between x and y in the plane of `group`: 1 when x and y lie
 * strictly on the same side of the plane and the point where x -> y' (y
 * reflected in the plane) crosses it lies inside one of the group's
 * triangles, which *triangle names (an index into mirror_triangles). */
static inline int wp_mirror_connect(const WpSceneView* scene, const WpMirrorGroup* group, float3 x,
                                    float3 y, float3* m, wp_uint* triangle) {
    float3 n = group->plane.xyz;
    float sx = dot(n, x) - group->plane.w;
    float sy = dot(n, y) - group->plane.w;
    if (!(sx * sy > 0.0f))
        return 0;
    /* x + s (y' - x) with y' = y - 2 sy n meets the plane at s = sx / (sx + sy). */
    float3 mirrored = y - (2.0f * sy) * n;
    float3 p = x + (sx / (sx + sy)) * (mirrored - x);
    p -= (dot(n, p) - group->plane.w) * n;
    *m = p;
#ifdef WP_MIRROR_GROUP_TRIANGLES
    /* The largest group's count compiled in: a fixed-count loop (no
     * data-dependent loop in shade, as for the light pick) that keeps the
     * first triangle holding p, as the loop below does. */
    int found = 0;
    _Pragma("unroll") for (wp_uint j = 0; j < (wp_uint)(WP_MIRROR_GROUP_TRIANGLES); ++j) {
        wp_uint k = group->first + j;
        if (j < group->count && !found && wp_mirror_triangle_holds(scene->mirror_triangles[k], p)) {
            *triangle = k;
            found = 1;
        }
    }
    return found;
#else
    for (wp_uint k = group->first; k < group->first + group->count; ++k) {
        if (wp_mirror_triangle_holds(scene->mirror_triangles[k], p)) {
            *triangle = k;
            return 1;
        }
    }
    return 0;
#endif
}

/* The mirrored strategy's solid-angle density at x of the direction to a light
 * point seen at unfolded distance `distance` with cosine `cos_light`. */
static inline float wp_mirror_light_pdf(const WpSceneView* scene, float distance, float cos_light) {
    return distance * distance / (cos_light * scene->light_area * (float)scene->mirror_group_count);
}

/* The mirrored light sample at the diffuse surface point `surface` (ray
 * direction `wo`, shading normal on the lit side `shading`, shadow rays
 * from `origin`): 1 and *out when it carries light. */
static inline int wp_mirror_next_event(const WpSceneView* scene, const WpMaterial* material,
                                       const WpSurface* surface, float3 wo, float3 shading,
                                       float3 origin, float3 beta, float u_pick, float u, float v,
                                       WpMirrorShadow* out) {
    wp_uint groups = scene->mirror_group_count;
    if (groups == 0u || scene->light_count == 0u)
        return 0;
    float stretched = u_pick * (float)groups;
    wp_uint g = min((wp_uint)stretched, groups - 1u);
    u_pick = fmin(stretched - (float)g, 0x1.fffffep-1f);
    WpMirrorGroup group = scene->mirror_groups[g];
    WpTriangle light =
        scene->triangles[scene->lights[wp_pick_light(scene->lights, scene->light_count, u_pick)]
                             .triangle];
    float3 y = wp_sample_triangle(light.v0.xyz, light.v1.xyz, light.v2.xyz, u, v);
    float3 x = surface->position;
    float3 m;
    wp_uint k;
    if (!wp_mirror_connect(scene, &group, x, y, &m, &k))
        return 0;
    float3 n = group.plane.xyz;
    float3 mirrored = y - (2.0f * (dot(n, y) - group.plane.w)) * n;
    float3 to_image = mirrored - x;
    float distance = length(to_image);
    float3 wi = to_image / distance;
    float3 light_normal = normalize(wp_triangle_normal(&light));
    float3 image_normal = light_normal - (2.0f * dot(light_normal, n)) * n;
    float cos_surface = dot(shading, wi);
    float cos_light = -dot(image_normal, wi);
    if (!(cos_surface > 0.0f && cos_light > 0.0f))
        return 0;

    /* Leg 1 stops short of the mirror, leg 2 starts off it on x's side and
     * stops short of the light. */
    WpTriangle mirror = scene->mirror_triangles[k];
    float mirror_scale = wp_triangle_scale(&mirror);
    float3 leg1 = m - origin;
    float length1 = length(leg1);
    float test1 = length1 - wp_shadow_end_margin(m, mirror_scale, length1);
    float3 side = dot(n, x) > group.plane.w ? n : -n;
    float3 start2 = wp_offset_ray_origin(m, side, mirror_scale);
    float3 leg2 = y - start2;
    float length2 = length(leg2);
    float test2 = length2 - wp_shadow_end_margin(y, wp_triangle_scale(&light), length2);
    if (!(test1 > 0.0f && test2 > 0.0f))
        return 0;

    float p_mirror = wp_mirror_light_pdf(scene, distance, cos_light);
    float p_bsdf = wp_bsdf_pdf(material, wo, wi, shading);
    float weight = wp_mis_power(p_mirror, p_bsdf);
    float3 emission = scene->materials[wp_triangle_material(&light)].emission.xyz;
    float3 reflectance = scene->materials[wp_triangle_material(&mirror)].reflectance.xyz;
    float3 contribution = beta * wp_bsdf_eval_pi(material, wo, wi, shading) * (1.0f / WP_PI) *
                          emission * reflectance * (cos_surface * weight / p_mirror);
    if (wp_is_black(contribution))
        return 0;
    out->origin = (float4)(origin, 0.0f);
    out->direction = (float4)(leg1 / length1, test1);
    out->origin2 = (float4)(start2, 0.0f);
    out->direction2 = (float4)(leg2 / length2, test2);
    out->contribution = (float4)(contribution, 0.0f);
    return 1;
}

/* Whether the mirrored estimate at a diffuse vertex with these flags is of a
 * path type the render adds (path_type.h): its history is the vertex's, then
 * a mirror. */
#ifdef WP_PATH_TYPE_MASK
#define WP_MIRROR_NEXT_EVENT_SELECTED(flags)                                                       \
    wp_path_type_selected(                                                                         \
        wp_path_history_after(wp_path_history_after(wp_path_history(flags), 0), 1))
#else
#define WP_MIRROR_NEXT_EVENT_SELECTED(flags) 1
#endif

/* The weight of emission found by BSDF sampling after diffuse x -> planar
 * mirror -> this light point: `vertex` is x and its BSDF density, the ray
 * came from `mirror_origin` (just off the mirror point) `t` along `direction`
 * and met the light's front face at `surface`, of `primitive`. */
static inline float wp_mirror_emission_weight(const WpSceneView* scene, wp_uint primitive,
                                              float4 vertex, float3 mirror_origin, float t,
                                              const WpSurface* surface, float3 direction) {
    /* Only emissive triangles are lights the mirrored strategy samples. */
    if (scene->light_count == 0u || scene->mirror_group_count == 0u ||
        wp_primitive_kind(scene, primitive) != WP_PRIMITIVE_TRIANGLE)
        return 1.0f;
    float distance = length(mirror_origin - vertex.xyz) + t;
    float cos_light = -dot(surface->normal, direction);
    if (!(cos_light > 0.0f))
        return 1.0f;
    return wp_mis_power(vertex.w, wp_mirror_light_pdf(scene, distance, cos_light));
}

/* 1 if a specular bounce at this surface is off a planar mirror (a flat
 * mirror triangle: the host puts every one in a WpMirrorGroup). */
static inline int wp_is_planar_mirror(const WpSceneView* scene, wp_uint primitive,
                                      const WpSurface* surface) {
    return wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_TRIANGLE && !surface->smooth;
}

#endif /* WP_MIRROR_LIGHT_H */
