/* Next-event estimation: sampling a point on the area lights.
 *
 * Lights are the emissive triangles. One is picked with probability
 * proportional to its area, or, with WP_HAS_POWER_LIGHT_PICK, to its power
 * (area times luminance), then a point on it: uniformly by area (the point's
 * density is 1 / wp_light_area: by area 1 / (total light area) over all
 * lights), or, with WP_LIGHT_SAMPLING == WP_LIGHT_SOLID_ANGLE, uniformly in
 * the solid angle the triangle subtends (estimator.h). */
#ifndef WP_LIGHTS_H
#define WP_LIGHTS_H

#include "estimator.h"
#include "lights/envmap.h"
#include "lights/sphere.h"
#include "ray_offset.h"
#include "sampling.h"
#include "scene_features.h" /* WP_HAS_EMITTERS and the kinds' switches */
#include "stage.h"
#include "triangle.h"

/* Shadow rays stop this many offsets short of the light point, so the light
 * itself is never taken for an occluder. */
#define WP_SHADOW_END_MARGIN 4.0f

/* How far short of its end point `end` (on a primitive whose coordinates
 * reach `scale`) a shadow segment of length `length` stops: the margin above,
 * in offsets of the end's magnitude or of the segment's length, whichever is
 * larger. A hit's t carries the rounding of the unit direction, a few ulps of
 * the distance travelled, so a segment much longer than its end primitive's
 * coordinates (a small light 1e3 away) would otherwise meet the light's own
 * plane before it stops (docs/stability.md, case 9). */
static inline float wp_shadow_end_margin(float3 end, float scale, float length) {
    return WP_SHADOW_END_MARGIN * wp_offset_distance(end, fmax(scale, length));
}

#if WP_HAS_SPHERE_LIGHT
/* How long the shadow ray from `from` along the sampled direction wi may be
 * (t: the sample's distance to the sphere): up to where the intersection
 * test itself meets the sphere along the rounded wi, less the shadow ray's
 * end margin. The sample's own t will not do: near the cone's rim the
 * sphere is met at a grazing angle, where a direction rounded by an ulp
 * moves the hit by far more than the margin, and the sphere would shadow
 * its own light (measured: a floor under a sphere 30 radii away got 2.5 %
 * of its light). A rounded direction that passes the rim meets nothing: it
 * keeps the sample's t. */
static inline float wp_sphere_light_shadow_length(float3 from, float3 wi, float4 center_radius,
                                                  float t) {
    float t_hit;
    if (wp_sphere_test(from.x, from.y, from.z, wi.x, wi.y, wi.z, center_radius.x, center_radius.y,
                       center_radius.z, center_radius.w, 2.0f * t + 4.0f * center_radius.w, &t_hit))
        t = t_hit;
    return t - wp_shadow_end_margin(from + t * wi, center_radius.w, t);
}
#endif

/* The first light whose cumulative area fraction exceeds u (count > 0; the
 * last if none does). With the count compiled in (WP_LIGHT_COUNT, small
 * scenes) by binary search in its fixed number of steps, ceil(log2(count)),
 * each a select, so that no loop whose trip count depends on the data stands
 * in the way of vectorising shade (docs/profiling.md, "Vectorising shade").
 * Otherwise from the guide entry of u's bin of width 1 / count (WpLight.guide):
 * a step or two forwards on average however many lights there are (a scene
 * of 10^4 emitting triangles: bench/many_lights.py), and back where float
 * rounding put the bin one too far, so that it finds exactly the light the
 * binary search finds: images do not depend on how the search goes. */
static inline wp_uint wp_pick_light(__global const WpLight* lights, wp_uint count, float u) {
#ifdef WP_LIGHT_COUNT
    wp_uint low = 0, high = count - 1u;
    _Pragma("unroll") for (wp_uint span = (wp_uint)(WP_LIGHT_COUNT)-1u; span > 0u; span >>= 1) {
        wp_uint mid = (low + high) / 2u;
        int left = lights[mid].cdf > u;
        int searching = low < high;
        high = searching && left ? mid : high;
        low = searching && !left ? mid + 1u : low;
    }
    return low;
#else
    wp_uint j = lights[min((wp_uint)(u * (float)count), count - 1u)].guide;
    j = min(j, count - 1u); /* a table without guides (0) or a prefix of one */
    while (j + 1u < count && lights[j].cdf <= u)
        ++j;
    while (j > 0u && lights[j - 1u].cdf > u)
        --j;
    return j;
#endif
}

/* 1 / the density per unit area with which the pick and a uniform point on
 * the light triangle `light` choose a point of it: the total emissive area by
 * area; by power, the total power over the light's own radiance's luminance,
 * which the host stores in its material's emission.w (render/light_pick.hpp;
 * the total area there too where the pick is by area, so the general kernels
 * give the area pick's bits). A material made without it (w 0, as kernel
 * tests build them) is picked by area. */
static inline float wp_light_area(const WpSceneView* scene, const WpTriangle* light) {
#if WP_HAS_POWER_LIGHT_PICK
    float area = scene->materials[wp_triangle_material(light)].emission.w;
    return area > 0.0f ? area : scene->light_area;
#else
    (void)light;
    return scene->light_area;
#endif
}

/* A light sample as seen from a surface point. */
typedef struct {
    float3 origin;     /* where the shadow ray starts (the surface's lit side) */
    float3 direction;  /* unit, from the shadow-ray origin towards the light */
    float length;      /* how far the shadow ray must stay unblocked */
    float3 irradiance; /* Le * cos_surface * cos_light / d^2 / pdf: multiply by the BRDF */
    float pdf;         /* the solid-angle density of direction (for MIS); INFINITY: a delta light */
    int weigh_always;  /* weighed against BSDF sampling at every non-delta vertex (the constant
                          emitter, which a BSDF sample finds by escaping) */
} WpLightSample;

/* The power heuristic's weight of the strategy of density `own` against
 * `other` (0 when its own density is 0, 1 when the other's is). */
static inline float wp_mis_power(float own, float other) {
    if (!(own > 0.0f))
        return 0.0f;
    float r = other / own;
    return 1.0f / (1.0f + r * r);
}

/* The weight of a light sample of density `light_pdf` (INFINITY: a delta
 * light) against BSDF sampling's `bsdf_pdf` of the same direction, and of a
 * BSDF-sampled hit on a light against the light sample that could have found
 * it, by WP_MIS_STRATEGY (estimator.h). */
static inline float wp_mis_light_sample(float light_pdf, float bsdf_pdf) {
#if WP_MIS_STRATEGY == WP_MIS_LIGHT_ONLY
    (void)light_pdf, (void)bsdf_pdf;
    return 1.0f;
#else
    return wp_mis_power(light_pdf, bsdf_pdf);
#endif
}

static inline float wp_mis_bsdf_hit(float bsdf_pdf, float light_pdf) {
#if WP_MIS_STRATEGY == WP_MIS_LIGHT_ONLY
    (void)bsdf_pdf;
    return light_pdf > 0.0f ? 0.0f : 1.0f;
#else
    return wp_mis_power(bsdf_pdf, light_pdf);
#endif
}

/* The shadow ray from `origin` to a light point, stopping just short of it. */
static inline int wp_aim_shadow_ray(float3 origin, float3 point, const WpTriangle* light,
                                    WpLightSample* out) {
    float3 ray = point - origin;
    float ray_length = length(ray);
    float length_to_test =
        ray_length - wp_shadow_end_margin(point, wp_triangle_scale(light), ray_length);
    if (!(length_to_test > 0.0f))
        return 0;
    out->origin = origin;
    out->direction = ray / ray_length;
    out->length = length_to_test;
    return 1;
}

/* Samples the lights as seen from the surface point `position` (normal on the
 * lit side `normal`); the shadow ray starts at `origin`, the point offset off
 * the surface. With `two_sided` (a BSDF that transmits) a light behind the
 * surface counts too, by the cosine's magnitude, and its shadow ray starts at
 * `origin_behind`, offset to the other side. The geometry term belongs to the surface point: taken
 * at the offset origin it biased a light 1e-3 above a floor by 8 % (the offset was 4 % of the gap;
 * docs/stability.md, case 6). Returns 0 when the point faces away, the light faces away (lights are
 * one-sided), or nothing can arrive. */
static inline int wp_sample_light(const WpSceneView* scene, float3 position, float3 origin,
                                  float3 origin_behind, int two_sided, float3 normal, float u_pick,
                                  float u, float v, WpLightSample* out) {
    if (scene->light_count == 0u) /* general kernels may meet a scene without lights */
        return 0;
    WpTriangle light =
        scene->triangles[scene->lights[wp_pick_light(scene->lights, scene->light_count, u_pick)]
                             .triangle];
    float light_area = wp_light_area(scene, &light);
    float3 light_normal = normalize(wp_triangle_normal(&light));
#if WP_LIGHT_SAMPLING == WP_LIGHT_SOLID_ANGLE
    /* Uniform in the triangle's solid angle Omega: the direction's density is
     * p_pick / Omega, p_pick = area / light_area. Lights are one-sided, so a
     * point behind the light's plane gets nothing. */
    float3 r0 = light.v0.xyz - position, r1 = light.v1.xyz - position, r2 = light.v2.xyz - position;
    float plane_distance = -dot(r0, light_normal); /* > 0 in front of the light */
    float solid_angle = wp_spherical_triangle_area(r0, r1, r2);
    if (plane_distance > 0.0f && solid_angle >= WP_MIN_SPHERICAL_AREA &&
        solid_angle <= WP_MAX_SPHERICAL_AREA) {
        float3 wi = wp_sample_spherical_triangle(normalize(r0), normalize(r1), normalize(r2),
                                                 solid_angle, u, v);
        float cos_surface = dot(normal, wi);
        float cos_light = -dot(light_normal, wi);
        float3 from = origin;
        if (two_sided && cos_surface < 0.0f) {
            cos_surface = -cos_surface;
            from = origin_behind;
        }
        if (!(cos_surface > 0.0f && cos_light > 0.0f))
            return 0;
        float distance = plane_distance / cos_light; /* along wi to the light's plane */
        float3 point = position + distance * wi;
        if (!wp_aim_shadow_ray(from, point, &light, out))
            return 0;
        float triangle_area =
            0.5f * length(cross(light.v1.xyz - light.v0.xyz, light.v2.xyz - light.v0.xyz));
        out->irradiance = scene->materials[wp_triangle_material(&light)].emission.xyz *
                          (cos_surface * solid_angle * light_area / triangle_area);
        out->pdf = triangle_area / (light_area * solid_angle);
        return 1;
    }
    /* Too small (or too large) a solid angle for float: area sampling below. */
#endif
    float3 point = wp_sample_triangle(light.v0.xyz, light.v1.xyz, light.v2.xyz, u, v);
    float3 to_light = point - position;
    float distance = length(to_light);
    float3 wi = to_light / distance;
    float cos_surface = dot(normal, wi);
    float cos_light = -dot(light_normal, wi);
    float3 from = origin;
    if (two_sided && cos_surface < 0.0f) {
        cos_surface = -cos_surface;
        from = origin_behind;
    }
    if (!(cos_surface > 0.0f && cos_light > 0.0f) || !wp_aim_shadow_ray(from, point, &light, out))
        return 0;
    float geometry = cos_surface * cos_light / (distance * distance);
    out->irradiance =
        scene->materials[wp_triangle_material(&light)].emission.xyz * (geometry * light_area);
    out->pdf = distance * distance / (cos_light * light_area);
    return 1;
}

/* The solid-angle density with which wp_sample_light, at `position`, picks the
 * direction to `point` on the front face of the light triangle `light` (what
 * multiple importance sampling weighs a BSDF-sampled hit on a light with). */
static inline float wp_light_pdf(const WpSceneView* scene, const WpTriangle* light, float3 position,
                                 float3 point) {
    float3 light_normal = normalize(wp_triangle_normal(light));
    float3 to_light = point - position;
    float distance = length(to_light);
    float cos_light = -dot(light_normal, to_light / distance);
    if (!(cos_light > 0.0f) || scene->light_count == 0u)
        return 0.0f;
#if WP_LIGHT_SAMPLING == WP_LIGHT_SOLID_ANGLE
    float3 r0 = light->v0.xyz - position, r1 = light->v1.xyz - position,
           r2 = light->v2.xyz - position;
    float solid_angle = wp_spherical_triangle_area(r0, r1, r2);
    if (-dot(r0, light_normal) > 0.0f && solid_angle >= WP_MIN_SPHERICAL_AREA &&
        solid_angle <= WP_MAX_SPHERICAL_AREA) {
        float triangle_area =
            0.5f * length(cross(light->v1.xyz - light->v0.xyz, light->v2.xyz - light->v0.xyz));
        return triangle_area / (wp_light_area(scene, light) * solid_angle);
    }
#endif
    return distance * distance / (cos_light * wp_light_area(scene, light));
}

#if WP_HAS_EMITTERS
/* Mitsuba 3's spot falloff, as 3.9.1 computes it (measured with its
 * scalar_rgb variant, docs/lights-and-camera.md): 1 within beam_width of the
 * axis, then linear in the angle down to 0 at cutoff_angle, 0 from there on.
 * `cos_theta` is the cosine between the axis and the direction leaving the
 * light. */
static inline float wp_spot_falloff(__global const WpEmitter* e, float cos_theta) {
    if (!(cos_theta > e->cos_cutoff))
        return 0.0f;
    if (cos_theta >= e->cos_beam)
        return 1.0f;
    return (e->cutoff - acos(fmin(cos_theta, 1.0f))) * e->inv_transition;
}

/* Samples emitter `e` (not an emissive triangle) from the surface point
 * `position`, as wp_sample_light samples a triangle: the irradiance is
 * divided by the probability of choosing the emitter (e->pick). Point, spot
 * and directional emitters are delta lights, reached by this sample alone:
 * their pdf is INFINITY, which gives them the power heuristic's weight 1. The
 * constant emitter samples a direction uniformly on the sphere (pdf
 * pick / (4 pi)), an envmap by its image (lights/envmap.h): what a ray that
 * escapes weighs itself against (shade.cl). */
static inline int wp_sample_emitter(const WpSceneView* scene, __global const WpEmitter* e,
                                    float3 position, float3 origin, float3 origin_behind,
                                    int two_sided, float3 normal, float u, float v,
                                    WpLightSample* out) {
    wp_uint kind = e->kind;
    float3 wi;
    float length_to_test;
    float3 arriving = e->radiance.xyz * (1.0f / e->pick); /* at normal incidence, over the pdf */
    float pdf = INFINITY;
    out->weigh_always = 0;
    if (kind == WP_EMITTER_CONSTANT || kind == WP_EMITTER_DIRECTIONAL ||
        kind == WP_EMITTER_ENVMAP) {
        /* Nothing to stop short of: the shadow ray must only leave the scene. */
        length_to_test = e->reach;
        wi = -e->direction.xyz;
#if WP_HAS_CONSTANT_LIGHT
        if (kind == WP_EMITTER_CONSTANT) {
            wi = wp_sample_uniform_sphere(u, v);
            pdf = e->pick * (1.0f / (4.0f * WP_PI));
            arriving = e->radiance.xyz * (1.0f / pdf);
            out->weigh_always = 1;
        }
#endif
#if WP_HAS_ENVMAP_LIGHT
        if (kind == WP_EMITTER_ENVMAP) {
            float direction_pdf;
            float3 radiance;
            wp_envmap_sample(scene->texels, scene->environment_cdf, e, u, v, &wi, &direction_pdf,
                             &radiance);
            if (!(direction_pdf > 0.0f))
                return 0;
            pdf = e->pick * direction_pdf;
            arriving = radiance * (1.0f / pdf);
            out->weigh_always = 1;
        }
#endif
#if WP_HAS_SPHERE_LIGHT
    } else if (kind == WP_EMITTER_SPHERE) {
        /* Uniform in the cone the sphere subtends (lights/sphere.h); found by
         * a BSDF sample too, so weighed as a triangle is (shade.cl). */
        float t, cone_pdf;
        if (!wp_sample_sphere_light(position, e->position, u, v, &wi, &t, &cone_pdf))
            return 0;
        pdf = e->pick * cone_pdf;
        arriving = e->radiance.xyz * (1.0f / pdf);
        length_to_test = t; /* made the shadow ray's below, from where it starts */
#endif
    } else { /* point, spot: intensity over the squared distance */
        float3 to_light = e->position.xyz - position;
        float distance_squared = dot(to_light, to_light);
        float distance = sqrt(distance_squared);
        if (!(distance > 0.0f))
            return 0;
        wi = to_light / distance;
        arriving *= 1.0f / distance_squared;
#if WP_HAS_SPOT_LIGHT
        if (kind == WP_EMITTER_SPOT)
            arriving *= wp_spot_falloff(e, -dot(wi, e->direction.xyz));
#endif
        length_to_test = distance - wp_shadow_end_margin(e->position.xyz, 0.0f, distance);
    }
    (void)scene, (void)u, (void)v;
    float cos_surface = dot(normal, wi);
    float3 from = origin;
    if (two_sided && cos_surface < 0.0f) {
        cos_surface = -cos_surface;
        from = origin_behind;
    }
#if WP_HAS_SPHERE_LIGHT
    if (kind == WP_EMITTER_SPHERE)
        length_to_test = wp_sphere_light_shadow_length(from, wi, e->position, length_to_test);
#endif
    if (!(cos_surface > 0.0f && length_to_test > 0.0f))
        return 0;
    out->origin = from;
    out->direction = wi;
    out->length = length_to_test;
    out->irradiance = arriving * cos_surface;
    out->pdf = pdf;
    return 1;
}
#endif

#if WP_HAS_SPHERE_LIGHT
/* The density with which next-event estimation, at `position`, picks a
 * direction towards sphere number `sphere` (0 if that sphere is not a
 * light): what a BSDF-sampled hit on it is weighed against. The few
 * emitters are searched for the sphere's. */
static inline float wp_sphere_light_pick_pdf(const WpSceneView* scene, wp_uint sphere,
                                             float3 position) {
    for (wp_uint i = 0u; i < scene->emitter_count; ++i) {
        __global const WpEmitter* e = &scene->emitters[i];
        if (e->kind == WP_EMITTER_SPHERE && e->sphere == sphere)
            return e->pick * wp_sphere_light_pdf(position, e->position);
    }
    return 0.0f;
}
#endif

/* Next-event estimation's light sample over every light of the scene: with
 * emitters other than triangles (WP_HAS_EMITTERS), first the choice between
 * the emissive triangles (probability 1 - scene->emitter_pick, then one of
 * them as wp_sample_light does, its number u_pick rescaled) and each
 * emitter (its `pick`), by emitted power (src/render/device_scene.cpp); the
 * sample's irradiance is divided by the probability and its pdf multiplied,
 * so that multiple importance sampling weighs it with the density it really
 * had. Without emitters, wp_sample_light itself, unchanged. */
static inline int wp_sample_lights(const WpSceneView* scene, float3 position, float3 origin,
                                   float3 origin_behind, int two_sided, float3 normal, float u_pick,
                                   float u, float v, WpLightSample* out) {
#if WP_HAS_EMITTERS
    float area_pick = 1.0f - scene->emitter_pick;
    if (u_pick < area_pick) {
#if WP_HAS_LIGHTS
        if (!wp_sample_light(scene, position, origin, origin_behind, two_sided, normal,
                             u_pick / area_pick, u, v, out))
            return 0;
        out->irradiance *= 1.0f / area_pick;
        out->pdf *= area_pick;
        out->weigh_always = 0;
        return 1;
#else
        return 0;
#endif
    }
    if (scene->emitter_count == 0u) /* general kernels may meet a scene without emitters */
        return 0;
    /* A few emitters: a linear search of their cumulative probabilities. */
    wp_uint i = 0u;
    while (i + 1u < scene->emitter_count && scene->emitters[i].cdf <= u_pick)
        ++i;
    return wp_sample_emitter(scene, &scene->emitters[i], position, origin, origin_behind, two_sided,
                             normal, u, v, out);
#else
    out->weigh_always = 0;
    return wp_sample_light(scene, position, origin, origin_behind, two_sided, normal, u_pick, u, v,
                           out);
#endif
}

#endif /* WP_LIGHTS_H */
