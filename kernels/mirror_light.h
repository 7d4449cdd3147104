/* Next-event estimation through mirrors (WP_MIRROR_NEE): planar mirrors and
 * mirror spheres.
 *
 * No shadow ray finds a light by way of a mirror, so without this the light
 * a mirror throws onto diffuse surfaces (a caustic) is found only by paths
 * that bounce diffuse -> mirror -> light, a few bright samples.
 *
 * Planar mirrors. The light's mirror image is exact: from a diffuse point x,
 * sample a point y on the lights (as lights.h does), reflect it in
 * the mirror's plane (y'), and the segment x -> y' meets the plane at the
 * mirror point m, which must lie inside the mirror's outline (one of its
 * triangles). If both legs, x -> m and m -> y, are unblocked the light
 * arrives with
 *     f(x) Le R(m) cos_x cos_y / |x - y'|^2 / p(y),
 * cos_y taken against the reflected direction (the image of the light is
 * seen at distance |x - y'| = |x - m| + |m - y|).
 *
 * Mirror spheres (convex, curved). For x and y outside a sphere there is at
 * most one point m on it that both see and where a ray from x reflects to y
 * (the arc between the sphere's points towards x and towards y holds it;
 * wp_sphere_mirror_point finds it by regula falsi). The light's image is no
 * longer a flat copy: a convex mirror spreads the beam, differently in the
 * plane of incidence (tangential) and across it (sagittal), by the mirror's
 * focal powers 2 / (R cos_m) and 2 cos_m / R at incidence cosine cos_m
 * (Coddington's equations). A pencil of solid angle dw from x lands on the light on
 *     dA_y = dw (d1 + d2 + 2 d1 d2 / (R cos_m)) (d1 + d2 + 2 d1 d2 cos_m / R) / cos_y,
 * d1 = |x - m|, d2 = |m - y|, which for R -> infinity is the planar mirror's
 * (d1 + d2)^2 / cos_y (tests/render/test_sphere_mirror.cpp checks it
 * against finite differences of traced rays in double precision).
 *
 * The path diffuse x -> mirror -> light found by sampling the BSDF at x
 * finds the same light, so the two strategies are combined by multiple
 * importance sampling (the power heuristic): each weighs its sample by its
 * own solid-angle density at x against the other's,
 *     p_bsdf(x, wi)   the diffuse BSDF's density of the direction wi,
 *     p_mirror(wi) = dA_y / dw / (cos_y * wp_light_area * mirror count),
 * and the weights of the two sum to 1 for every path, so nothing is counted
 * twice or lost. The mirrored strategy picks its mirror uniformly among the
 * scene's planar mirrors (WpMirrorGroup, src/render/planar_mirrors.hpp: the
 * host groups coplanar mirror triangles without vertex normals) and its
 * mirror spheres (mirror_spheres[], their numbers in spheres[]). Paths with
 * two or more mirror bounces keep weight 1.
 *
 * "Diffuse" above stands for any vertex that is not delta (a glossy one
 * does the same, with its own BSDF's density), and "mirror" for the `mirror`
 * material kind only (Mitsuba's conductor with material "none"): other
 * delta surfaces, such as a smooth conductor with a Fresnel term, are not
 * sampled by this strategy, and paths off them keep weight 1.
 *
 * The shading side (kernels/shade.cl) keeps the last diffuse vertex and its
 * BSDF density in mirror_vertex, and WP_PATH_PLANAR_MIRROR (or
 * WP_PATH_SPHERE_MIRROR with the sphere's number) in path_flags while the
 * path's last two vertices were diffuse, then a mirror; shade pushes the
 * two-leg ray onto the mirror queue (shadow_queue from pool_size on, its
 * length in counters[WP_COUNTER_MIRROR_SHADOW_RAYS]), which the kernel
 * mirror_shadow (kernels/shadow.cl) tests after the shadow stage.
 *
 * The light point reuses the numbers of the bounce's own next-event
 * estimation (the two estimates are each unbiased, so their sum is); the
 * mirror is picked by stretching the light-pick number.
 *
 * Compiled only with WP_MIRROR_NEE=1 (the host's --mirror-nee, default on),
 * in scenes with lights, next-event estimation and planar mirrors
 * (WP_HAS_PLANAR_MIRRORS) or mirror spheres (WP_HAS_MIRROR_SPHERES);
 * left undefined it is off, the original estimator.
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
#if !((WP_HAS_PLANAR_MIRRORS || WP_HAS_MIRROR_SPHERES) && WP_HAS_LIGHTS && WP_USE_NEE &&           \
      WP_HAS_TRIANGLES)
#undef WP_MIRROR_NEE
#define WP_MIRROR_NEE 0
#endif

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

/* How many mirrors the mirrored strategy picks among. */
static inline wp_uint wp_mirror_count(const WpSceneView* scene) {
#if WP_HAS_MIRROR_SPHERES
    return scene->mirror_group_count + scene->mirror_sphere_count;
#else
    return scene->mirror_group_count;
#endif
}

/* The mirrored strategy's solid-angle density at x of the direction to a light
 * point seen at unfolded distance `distance` with cosine `cos_light`, on a
 * light of wp_light_area `light_area` (lights.h). */
static inline float wp_mirror_light_pdf(const WpSceneView* scene, float light_area, float distance,
                                        float cos_light) {
    return distance * distance / (cos_light * light_area * (float)wp_mirror_count(scene));
}

/* The same through a mirror sphere of radius `radius`: x is d1 from the
 * mirror point, which the light point is d2 from, the ray meets the sphere
 * at incidence cosine `cos_mirror` (> 0) and the light at `cos_light`. */
static inline float wp_sphere_mirror_light_pdf(const WpSceneView* scene, float light_area, float d1,
                                               float d2, float cos_mirror, float radius,
                                               float cos_light) {
    float spread = 2.0f * d1 * d2 / radius;
    float tangential = d1 + d2 + spread / cos_mirror;
    float sagittal = d1 + d2 + spread * cos_mirror;
    return tangential * sagittal / (cos_light * light_area * (float)wp_mirror_count(scene));
}

/* Whether the mirrored strategy tries x and y around a sphere (centre c,
 * radius r): both strictly outside, and less than about 154 degrees apart as
 * seen from the centre (beyond, the reflection is so grazing that the arc
 * search below would lose precision). The emission weight asks the same, so
 * that the paths it leaves out keep weight 1 on the BSDF side. */
static inline int wp_sphere_mirror_tries(float3 c, float r, float3 x, float3 y) {
    float3 px = x - c, py = y - c;
    float lx = length(px), ly = length(py);
    return lx > r && ly > r && dot(px, py) > -0.9f * lx * ly;
}

/* The reflection point on the sphere (centre c, radius r) of the path
 * x -> m -> y, for x and y that wp_sphere_mirror_tries accepts. In the plane
 * of c, x and y, with a and b the unit directions from c to x and to y an
 * angle alpha apart, m = c + r (cos p a + sin p v) (v the unit direction
 * across a towards b) for the angle p in [0, alpha] at which the normal
 * bisects the directions to x and to y, where
 *     g(p) = ly sin(alpha - p) / |y - m| - lx sin p / |x - m|
 * (the difference of their tangential parts) vanishes: at p = 0 it is
 * positive, at p = alpha negative, and where x and y both see m it is the
 * only root (docs/convergence.md). In the half-angle tangent t = tan(p / 2)
 * (and w = tan((alpha - p) / 2)) every term is rational, no sine or cosine
 * to evaluate, and |x - m|^2 = (lx - r)^2 + 2 lx r (1 - cos p) keeps its
 * precision next to the sphere. Regula falsi with the Illinois step: the
 * root stays between the two ends, so the search stops once they are less
 * than WP_SPHERE_MIRROR_TOLERANCE apart (then m is within twice that, in
 * radii, of the true point), after at most WP_SPHERE_MIRROR_STEPS steps.
 * Half the pairs take 6 steps, 1 in 100 more than 11 (near-grazing
 * reflections; docs/performance.md, "Kept: the search stops when its bracket
 * is narrow"). Shade runs scalar on PoCL, where the early stop saves 15 % of
 * it; a shade made vectorisable (docs/profiling.md) needs the fixed count
 * back (tolerance 0). 1 and *m if both x and y see m. */
#define WP_SPHERE_MIRROR_STEPS 12
#define WP_SPHERE_MIRROR_TOLERANCE 1e-5f
static inline float wp_sphere_mirror_residual(float t, float tan_half_alpha, float lx, float ly,
                                              float near_x, float near_y, float r) {
    float w = (tan_half_alpha - t) / (1.0f + tan_half_alpha * t);
    float it = 1.0f / (1.0f + t * t);
    float iw = 1.0f / (1.0f + w * w);
    float sin_p = 2.0f * t * it, versin_p = 2.0f * t * t * it;
    float sin_q = 2.0f * w * iw, versin_q = 2.0f * w * w * iw; /* q = alpha - p */
    float to_x = near_x + 2.0f * lx * r * versin_p;            /* |x - m|^2 */
    float to_y = near_y + 2.0f * ly * r * versin_q;
    return ly * sin_q * rsqrt(to_y) - lx * sin_p * rsqrt(to_x);
}

static inline int wp_sphere_mirror_point(float3 c, float r, float3 x, float3 y, float3* m) {
    float3 px = x - c, py = y - c;
    float lx = length(px), ly = length(py);
    float3 a = px / lx, b = py / ly;
    float cos_alpha = dot(a, b);
    float3 across = b - cos_alpha * a;
    float sin_alpha = length(cross(a, b));
    float tan_half_alpha = sin_alpha / (1.0f + cos_alpha);
    float near_x = (lx - r) * (lx - r), near_y = (ly - r) * (ly - r);
    float t0 = 0.0f, t1 = tan_half_alpha;
    float g0 = wp_sphere_mirror_residual(t0, tan_half_alpha, lx, ly, near_x, near_y, r);
    float g1 = wp_sphere_mirror_residual(t1, tan_half_alpha, lx, ly, near_x, near_y, r);
    float t = 0.0f;
    int kept = 0; /* which end the last step kept: 1 the low one, -1 the high one */
    for (int i = 0; i < WP_SPHERE_MIRROR_STEPS && t1 - t0 > WP_SPHERE_MIRROR_TOLERANCE; ++i) {
        float denominator = g0 - g1;
        t = denominator > 0.0f ? t0 + (t1 - t0) * (g0 / denominator) : 0.5f * (t0 + t1);
        float g = wp_sphere_mirror_residual(t, tan_half_alpha, lx, ly, near_x, near_y, r);
        if (g > 0.0f) {
            t0 = t;
            g0 = g;
            g1 *= kept == -1 ? 0.5f : 1.0f; /* Illinois: the end kept twice, halved */
            kept = -1;
        } else {
            t1 = t;
            g1 = g;
            g0 *= kept == 1 ? 0.5f : 1.0f;
            kept = 1;
        }
    }
    float it = 1.0f / (1.0f + t * t);
    float across_length = length(across);
    float3 v = across_length > 0.0f ? across / across_length : (float3)(0.0f);
    float3 n = ((1.0f - t * t) * it) * a + (2.0f * t * it) * v;
    float3 point = c + r * n;
    *m = point;
    return dot(n, x - point) > 0.0f && dot(n, y - point) > 0.0f;
}

/* The mirrored light sample's contribution once the mirror point is known:
 * x (ray direction `wo`, shading point `point`) sees the
 * light point y with emission `emission` by way of m, direction `wi`, at
 * density `p_mirror`; leg 1 runs from `origin` to m (stopping short of it by
 * the margin of a primitive of scale `mirror_scale`), leg 2 from `start2`
 * (off the mirror on x's side) to y on `light`. 1 and *out when it carries
 * light. */
static inline int wp_mirror_shadow_ray(const WpMaterial* material, float3 wo,
                                       const WpShadingPoint* point, float3 origin, float3 beta,
                                       float3 m, float mirror_scale, float3 start2, float3 y,
                                       const WpTriangle* light, float3 wi, float cos_surface,
                                       float p_mirror, float3 emission, float3 reflectance,
                                       WpMirrorShadow* out) {
    float3 leg1 = m - origin;
    float length1 = length(leg1);
    float test1 = length1 - wp_shadow_end_margin(m, mirror_scale, length1);
    float3 leg2 = y - start2;
    float length2 = length(leg2);
    float test2 = length2 - wp_shadow_end_margin(y, wp_triangle_scale(light), length2);
    if (!(test1 > 0.0f && test2 > 0.0f))
        return 0;
    float p_bsdf = wp_bsdf_pdf(material, wo, wi, point);
    float weight = wp_mis_power(p_mirror, p_bsdf);
    float3 contribution = beta * wp_bsdf_eval_pi(material, wo, wi, point) * (1.0f / WP_PI) *
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

/* Through planar mirror `group` (the arguments as wp_mirror_next_event's). */
static inline int wp_planar_mirror_next_event(const WpSceneView* scene, const WpMaterial* material,
                                              const WpSurface* surface, float3 wo,
                                              const WpShadingPoint* point, float3 origin,
                                              float3 beta, const WpMirrorGroup* group,
                                              const WpTriangle* light, float3 y,
                                              WpMirrorShadow* out) {
    float3 x = surface->position;
    float3 m;
    wp_uint k;
    if (!wp_mirror_connect(scene, group, x, y, &m, &k))
        return 0;
    float3 n = group->plane.xyz;
    float3 mirrored = y - (2.0f * (dot(n, y) - group->plane.w)) * n;
    float3 to_image = mirrored - x;
    float distance = length(to_image);
    float3 wi = to_image / distance;
    float3 light_normal = normalize(wp_triangle_normal(light));
    float3 image_normal = light_normal - (2.0f * dot(light_normal, n)) * n;
    float cos_surface = dot(point->n, wi);
    float cos_light = -dot(image_normal, wi);
    if (!(cos_surface > 0.0f && cos_light > 0.0f))
        return 0;
    /* Leg 2 starts off the mirror on x's side. */
    WpTriangle mirror = scene->mirror_triangles[k];
    float mirror_scale = wp_triangle_scale(&mirror);
    float3 side = dot(n, x) > group->plane.w ? n : -n;
    float3 start2 = wp_offset_ray_origin(m, side, mirror_scale);
    return wp_mirror_shadow_ray(
        material, wo, point, origin, beta, m, mirror_scale, start2, y, light, wi, cos_surface,
        wp_mirror_light_pdf(scene, wp_light_area(scene, light), distance, cos_light),
        scene->materials[wp_triangle_material(light)].emission.xyz,
        scene->materials[wp_triangle_material(&mirror)].reflectance.xyz, out);
}

#if WP_HAS_MIRROR_SPHERES
/* Through mirror sphere `sphere` (the arguments as wp_mirror_next_event's). */
static inline int wp_sphere_mirror_next_event(const WpSceneView* scene, const WpMaterial* material,
                                              const WpSurface* surface, float3 wo,
                                              const WpShadingPoint* point, float3 origin,
                                              float3 beta, WpSphere sphere, const WpTriangle* light,
                                              float3 y, WpMirrorShadow* out) {
    float3 c = sphere.center_radius.xyz;
    float r = sphere.center_radius.w;
    float3 x = surface->position;
    float3 m;
    if (!wp_sphere_mirror_tries(c, r, x, y) || !wp_sphere_mirror_point(c, r, x, y, &m))
        return 0;
    float3 n = normalize(m - c);
    float3 to_mirror = m - x;
    float d1 = length(to_mirror);
    float3 wi = to_mirror / d1;
    float3 to_light = y - m;
    float d2 = length(to_light);
    float3 light_normal = normalize(wp_triangle_normal(light));
    float cos_surface = dot(point->n, wi);
    float cos_mirror = -dot(n, wi);
    float cos_light = -dot(light_normal, to_light / d2);
    if (!(cos_surface > 0.0f && cos_mirror > 0.0f && cos_light > 0.0f))
        return 0;
    float mirror_scale = wp_sphere_scale(sphere.center_radius);
    float3 start2 = wp_offset_ray_origin(m, n, mirror_scale);
    return wp_mirror_shadow_ray(material, wo, point, origin, beta, m, mirror_scale, start2, y,
                                light, wi, cos_surface,
                                wp_sphere_mirror_light_pdf(scene, wp_light_area(scene, light), d1,
                                                           d2, cos_mirror, r, cos_light),
                                scene->materials[wp_triangle_material(light)].emission.xyz,
                                scene->materials[sphere.material].reflectance.xyz, out);
}
#endif

/* The mirrored light sample at the diffuse surface point `surface` (ray
 * direction `wo`, shading point `point` (bsdf/interface.h), shadow rays
 * from `origin`): 1 and *out when it carries light. */
static inline int wp_mirror_next_event(const WpSceneView* scene, const WpMaterial* material,
                                       const WpSurface* surface, float3 wo,
                                       const WpShadingPoint* point, float3 origin, float3 beta,
                                       float u_pick, float u, float v, WpMirrorShadow* out) {
    wp_uint mirrors = wp_mirror_count(scene);
    if (mirrors == 0u || scene->light_count == 0u)
        return 0;
    float stretched = u_pick * (float)mirrors;
    wp_uint g = min((wp_uint)stretched, mirrors - 1u);
    u_pick = fmin(stretched - (float)g, 0x1.fffffep-1f);
    WpTriangle light =
        scene->triangles[scene->lights[wp_pick_light(scene->lights, scene->light_count, u_pick)]
                             .triangle];
    float3 y = wp_sample_triangle(light.v0.xyz, light.v1.xyz, light.v2.xyz, u, v);
#if WP_HAS_MIRROR_SPHERES
    if (g >= scene->mirror_group_count)
        return wp_sphere_mirror_next_event(
            scene, material, surface, wo, point, origin, beta,
            scene->spheres[scene->mirror_spheres[g - scene->mirror_group_count]], &light, y, out);
#endif
    WpMirrorGroup group = scene->mirror_groups[g];
    return wp_planar_mirror_next_event(scene, material, surface, wo, point, origin, beta, &group,
                                       &light, y, out);
}

/* Whether the mirrored estimate at a diffuse vertex with these flags is of a
 * path type the render adds (path_type.h): its history is the vertex's, then
 * a mirror. */
#if WP_PATH_TYPES
#define WP_MIRROR_NEXT_EVENT_SELECTED(types, flags)                                                \
    wp_path_type_selected(                                                                         \
        types, wp_path_history_after(wp_path_history_after(wp_path_history(flags), 0), 1))
#else
#define WP_MIRROR_NEXT_EVENT_SELECTED(types, flags) 1
#endif

/* The weight of emission found by BSDF sampling after diffuse x -> mirror ->
 * this light point: `vertex` is x and its BSDF density, `flags` the path's
 * (WP_PATH_PLANAR_MIRROR or WP_PATH_SPHERE_MIRROR with the sphere's number),
 * the ray came from `mirror_origin` (just off the mirror point) `t` along
 * `direction` and met the light's front face at `surface`, of `primitive`. */
static inline float wp_mirror_emission_weight(const WpSceneView* scene, wp_uint primitive,
                                              wp_uint flags, float4 vertex, float3 mirror_origin,
                                              float t, const WpSurface* surface, float3 direction) {
    /* Only emissive triangles are lights the mirrored strategy samples. */
    if (scene->light_count == 0u || wp_mirror_count(scene) == 0u ||
        wp_primitive_kind(scene, primitive) != WP_PRIMITIVE_TRIANGLE)
        return 1.0f;
    float cos_light = -dot(surface->normal, direction);
    if (!(cos_light > 0.0f))
        return 1.0f;
    WpTriangle light = scene->triangles[primitive];
    float light_area = wp_light_area(scene, &light);
#if WP_HAS_MIRROR_SPHERES
    if (flags & WP_PATH_SPHERE_MIRROR) {
        float4 sphere = scene->spheres[flags >> WP_PATH_SPHERE_SHIFT].center_radius;
        float3 c = sphere.xyz;
        float r = sphere.w;
        float3 x = vertex.xyz;
        if (!wp_sphere_mirror_tries(c, r, x, surface->position))
            return 1.0f;
        float3 n = normalize(mirror_origin - c);
        float3 m = c + r * n;
        float cos_mirror = dot(n, direction);
        if (!(cos_mirror > 0.0f))
            return 1.0f;
        float d1 = length(m - x);
        float d2 = length(surface->position - m);
        return wp_mis_power(vertex.w, wp_sphere_mirror_light_pdf(scene, light_area, d1, d2,
                                                                 cos_mirror, r, cos_light));
    }
#endif
    (void)flags;
    float distance = length(mirror_origin - vertex.xyz) + t;
    return wp_mis_power(vertex.w, wp_mirror_light_pdf(scene, light_area, distance, cos_light));
}

/* 1 if a bounce off a mirror at this surface is off a planar mirror (a flat
 * mirror triangle: the host puts every one in a WpMirrorGroup). */
static inline int wp_is_planar_mirror(const WpSceneView* scene, wp_uint primitive,
                                      const WpSurface* surface) {
    return wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_TRIANGLE && !surface->smooth;
}

/* The path flags after a bounce at this surface (`primitive`, of a material
 * of the `mirror` kind when `mirror`): the mirror flags say whether it was the
 * first mirror after a non-delta vertex (and which sphere), for the emission
 * weight at the next vertex. Only the mirror kind: the mirrored strategy
 * samples the scene's mirrors (the host's WpMirrorGroup and mirror_spheres,
 * both of that kind), and a path off any other delta surface (a smooth
 * conductor) keeps weight 1. */
static inline wp_uint wp_mirror_flags_after(const WpSceneView* scene, wp_uint flags,
                                            wp_uint primitive, const WpSurface* surface,
                                            int mirror) {
    wp_uint kept = flags & ~(WP_PATH_PLANAR_MIRROR | WP_PATH_SPHERE_MIRROR | WP_PATH_SPHERE_BITS);
    if (!mirror || (flags & WP_PATH_SPECULAR)) /* not a mirror right after a non-delta vertex */
        return kept;
    if (wp_is_planar_mirror(scene, primitive, surface))
        return kept | WP_PATH_PLANAR_MIRROR;
#if WP_HAS_MIRROR_SPHERES
    if (wp_primitive_kind(scene, primitive) == WP_PRIMITIVE_SPHERE)
        return kept | WP_PATH_SPHERE_MIRROR |
               ((primitive - scene->triangle_count) << WP_PATH_SPHERE_SHIFT);
#endif
    return kept;
}

#endif /* WP_MIRROR_LIGHT_H */
