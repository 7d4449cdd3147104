/* Stage 3, shade: what happens where each queued ray hit, in four steps.
 *
 *  1. Emission: an emitter's front face adds throughput x radiance, in full
 *     for camera rays and rays after a delta bounce. After a non-delta bounce
 *     the light sample made there could have found the same light, so the
 *     emission counts with the multiple importance sampling weight of the
 *     BSDF sample against that light sample (the power heuristic,
 *     WP_MIS_EVERY_VERTEX, bsdf.h). Where next-event estimation is not
 *     weighed (--mis light; the report's estimator at a Lambertian vertex)
 *     the light sample counted the light alone, and the emission counts 0:
 *     counting it again would count it twice. (With WP_USE_NEE=0 there is no
 *     step 2 and emitters count after every bounce.)
 *  2. Next-event estimation (surfaces that are not delta BSDFs): sample a
 *     point on the lights (lights.h) and queue one shadow ray carrying the
 *     contribution it would make if nothing blocks it, weighed against BSDF
 *     sampling as step 1's emission is.
 *  3. Scattering: the material's BSDF (bsdf.h) picks the next direction, the
 *     factor the throughput takes and what kind of bounce it was (flags).
 *     The new ray leaves by the side of the surface the sample's flags name
 *     (reflection: the side the ray came from; transmission: the other),
 *     offset to that side. A sample whose direction the geometric normal puts
 *     on the other side is absorbed: with shading normals (triangles with
 *     vertex normals, which shade by the interpolated normal and send rays
 *     from the terminator-fixed point, primitive.h) the geometric cosine
 *     decides, so no light leaks through the surface; whether light from
 *     below their flat facet arrives is the shadow ray's to say.
 *  4. Russian roulette: survive with probability min(1, max(throughput)) and
 *     divide survivors' throughput by it, which keeps the estimate unbiased;
 *     from bounce WP_ROULETTE_DEPTH on (estimator.h), before it always survive.
 *     With WP_ROULETTE_RULE == WP_ROULETTE_MITSUBA the probability is
 *     Mitsuba 3's, min(0.95, max(throughput) eta^2), eta^2 carried in
 *     throughput.w; with WP_ROULETTE_SQRT Cycles', min(1, sqrt(max(throughput)));
 *     with WP_ROULETTE_RELATIVE the throughput over the first bounce's, which
 *     throughput.w carries instead.
 *     Past frame.max_depth bounces a path is cut and counted; the cap is a
 *     guard against endless mirror corridors, not part of the estimator.
 *     With WP_PATH_LENGTH (Mitsuba's max_depth, estimator.h) it is part of
 *     it: the vertex at depth frame.max_depth ends its path after step 1.
 *     With WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT it is the report's albedo
 *     roulette instead (estimator.h, bsdf/diffuse.h).
 *
 * With WP_PATH_TYPES (path_type.h) emission and next-event estimation add
 * only the light of the path types in frame.path_types.
 *
 * Survivors go to the other ray queue, finished paths (missed, absorbed,
 * cut) to the finished queue.
 */
#include "bsdf.h"
#include "estimator.h"
#include "lights.h"
#include "mirror_light.h"
#include "path_type.h"
#include "prefetch.h"
#include "primitive.h"
#include "rng.h"
#include "stage.h"
#include "textures/texture.h"

/* The random numbers of one bounce of one path: the bounce's eight, drawn
 * together before the hit is shaded (wp_shade_numbers), and any number past
 * them on demand. */
typedef struct {
    wp_uint seed, pixel, sample, depth;
    float numbers[WP_DIMS_PER_BOUNCE];
} WpPathRandom;

static inline WP_ALWAYS_INLINE float wp_path_random(const WpPathRandom* r, wp_uint dimension) {
    if (dimension < WP_DIMS_PER_BOUNCE)
        return r->numbers[dimension];
    return wp_random(r->seed, r->pixel, r->sample, r->depth, dimension);
}

/* Whether the material emits at all (WpMaterial.emission: any kind may, and
 * non-negative, scene/validate.cpp). */
static inline int wp_material_emits(const WpMaterial* material) {
    return material->emission.x != 0.0f || material->emission.y != 0.0f ||
           material->emission.z != 0.0f;
}

/* Step 1: the emitted radiance the path sees at this surface, if it counts. */
static inline float3 wp_shade_emission(const WpMaterial* material, const WpSurface* surface,
                                       wp_uint path_types, wp_uint flags, float3 beta, float3 sum) {
    if ((!WP_USE_NEE || (flags & (WP_PATH_SPECULAR | WP_PATH_GLOSSY))) && surface->front_face &&
        WP_PATH_EMISSION_SELECTED(path_types, flags))
        sum += beta * material->emission.xyz;
    return sum;
}

/* Step 2: one shadow ray towards the light point the numbers (u_pick, u, v)
 * pick, with the contribution it carries if unblocked, into *shadow (the
 * shade kernel queues it, a fused kernel traces it at once). */
static inline void wp_shade_next_event(const WpSceneView* scene, const WpMaterial* material,
                                       const WpSurface* surface, float3 wo,
                                       const WpShadingPoint* point, float3 origin,
                                       float3 origin_behind, float3 beta, float u_pick, float u,
                                       float v, WpShadowRay* shadow) {
#if (WP_HAS_LIGHTS || WP_HAS_EMITTERS) && WP_USE_NEE
    WpLightSample light;
    /* A transmitting BSDF sees lights on both sides. */
    if (!wp_sample_lights(scene, surface->position, origin, origin_behind,
                          wp_bsdf_transmits(material), point->n, u_pick, u, v, &light))
        return;
#if WP_HAS_WEIGHED_VERTICES || WP_HAS_ENVIRONMENT
    /* Where BSDF samples' hits on lights count (wp_bsdf_weighs_light) every
     * light sample is weighed; the environment is weighed at every non-delta
     * vertex whatever the strategy, as the ray that escapes is. The BSDF's
     * density comes with its value (a rough BSDF evaluates once). */
    float bsdf_pdf;
    float3 contribution = beta *
                          wp_bsdf_eval_pi_pdf(material, wo, light.direction, point, &bsdf_pdf) *
                          light.irradiance * (1.0f / WP_PI);
    if (wp_bsdf_weighs_light(material) || light.weigh_always)
        contribution *= wp_mis_light_sample(light.pdf, bsdf_pdf);
#else
    float3 contribution = beta * wp_bsdf_eval_pi(material, wo, light.direction, point) *
                          light.irradiance * (1.0f / WP_PI);
#endif
    if (wp_is_black(contribution))
        return;
    shadow->origin = light.origin;
    shadow->direction = light.direction;
    shadow->length = light.length;
    shadow->contribution = contribution;
    shadow->made = 1;
#else
    (void)scene, (void)material, (void)surface, (void)wo, (void)point;
    (void)origin, (void)origin_behind, (void)beta;
    (void)u_pick, (void)u, (void)v, (void)shadow;
#endif
}

#if WP_HAS_ENVIRONMENT
/* What a path that escaped along `direction` with throughput `beta` gathers
 * from the environment `e` (a constant or an envmap emitter; nothing from
 * any other kind): after a non-delta bounce (flags), weighed against the
 * light sample there by the power heuristic, `bsdf_pdf` being the density
 * the BSDF sampled the direction with. */
static inline float3 wp_shade_environment(__global const WpEmitter* e,
                                          __global const float* environment_cdf,
                                          __global const wp_uint* texels, float3 direction,
                                          wp_uint flags, float bsdf_pdf, float3 beta) {
    float3 found = (float3)(0.0f);
    /* The light sample's density, needed only after a non-delta bounce (a
     * camera ray that misses, the commonest escape, weighs 1). */
    int weighed = WP_USE_NEE && !(flags & WP_PATH_SPECULAR);
    float light_pdf = 0.0f;
#if WP_HAS_CONSTANT_LIGHT
    if (e->kind == WP_EMITTER_CONSTANT) {
        found = e->radiance.xyz;
        light_pdf = e->pick * (1.0f / (4.0f * WP_PI));
    }
#endif
#if WP_HAS_ENVMAP_LIGHT
    if (e->kind == WP_EMITTER_ENVMAP) {
        /* One patch lookup (its two angles) serves the radiance and the density. */
        int i, j;
        float ax, ay;
        wp_envmap_patch(e, direction, &i, &j, &ax, &ay);
        found = wp_envmap_patch_radiance(texels, e, i, j, ax, ay);
        if (weighed)
            light_pdf = e->pick * wp_envmap_patch_pdf(environment_cdf, e, i, j);
    }
#else
    (void)environment_cdf, (void)texels, (void)direction;
#endif
    if (weighed)
        found *= wp_mis_bsdf_hit(bsdf_pdf, light_pdf);
    return beta * found;
}
#endif

/* Step 4: whether the path goes on, and the probability it did so with
 * (survivors' throughput is divided by it). Takes the scattering weight into
 * *beta, and with Mitsuba's rule the sample's relative index of refraction
 * into *eta_squared. `u_bsdf` is the first number the BSDF sample used: the
 * report's roulette decides by it (bsdf/diffuse.h). */
static inline int wp_shade_roulette(const WpMaterial* material, const WpBsdfSample* scattered,
                                    const WpPathRandom* random, float u_bsdf, float3* beta,
                                    float* eta_squared, float* survival) {
#if WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT
    /* The report's roulette: survive with the surface's albedo sigma, whatever
     * the path carries; eq. 2.10 divides survivors by it. Only the diffuse
     * BSDF folds it into its sample (bsdf/diffuse.h); every other kind draws
     * a number of its own. */
    float u_survive =
        material->kind == WP_MATERIAL_DIFFUSE ? u_bsdf : wp_path_random(random, WP_DIM_ROULETTE);
    *survival = fmin(1.0f, wp_max_component(material->reflectance.xyz));
    *beta *= scattered->weight;
    (void)eta_squared;
    return u_survive < *survival;
#else
    (void)material;
    (void)u_bsdf;
    *beta *= scattered->weight;
#if WP_ROULETTE_RULE == WP_ROULETTE_MITSUBA
    *eta_squared *= scattered->eta * scattered->eta;
#elif WP_ROULETTE_RULE != WP_ROULETTE_RELATIVE
    (void)eta_squared;
#endif
#if WP_ROULETTE_RULE == WP_ROULETTE_RELATIVE
    if (random->depth == 0u) /* the first bounce's throughput: what the rest is relative to */
        *eta_squared = wp_max_component(*beta);
#endif
    if (random->depth + 1u < WP_ROULETTE_DEPTH) { /* every path survives its first bounces */
        *survival = 1.0f;
        return 1;
    }
#if WP_ROULETTE_RULE == WP_ROULETTE_MITSUBA
    *survival = fmin(0.95f, wp_max_component(*beta) * *eta_squared);
#elif WP_ROULETTE_RULE == WP_ROULETTE_SQRT
    *survival = fmin(1.0f, sqrt(wp_max_component(*beta)));
#elif WP_ROULETTE_RULE == WP_ROULETTE_RELATIVE
    /* 0 where the first bounce carried nothing on (then neither does beta) */
    *survival = *eta_squared > 0.0f ? fmin(1.0f, wp_max_component(*beta) / *eta_squared) : 0.0f;
#else
    *survival = fmin(1.0f, wp_max_component(*beta));
#endif
    return wp_path_random(random, WP_DIM_ROULETTE) < *survival;
#endif
}

/* The AOVs (WP_AOV): a camera ray's first hit adds, to its pixel's sums, the
 * material's albedo (the reflectance-like colour each kind stores in
 * `reflectance`, wp_shared.h; an emitter's is 0), the shading normal on the
 * side the ray came from (world space, unit) and the distance along the ray
 * (the direction is unit, generate.cl). A ray that misses adds nothing: 0.
 * The slot owns the pixel (WpFrame), so no atomics are needed. Writes
 * through the buffers, returns nothing (kernels/shade.cl is inlined whole). */
#if WP_AOV
static inline void wp_shade_aovs(const WpMaterial* material, const WpSurface* surface, float t,
                                 wp_uint pixel, __global float4* aov_albedo,
                                 __global float4* aov_normal, __global float* aov_depth) {
    float3 albedo =
        material->kind == WP_MATERIAL_EMITTER ? (float3)(0.0f) : material->reflectance.xyz;
    float3 normal = surface->front_face ? surface->shading_normal : -surface->shading_normal;
    aov_albedo[pixel] += (float4)(albedo, 0.0f);
    aov_normal[pixel] += (float4)(normal, 0.0f);
    aov_depth[pixel] += t;
}
#endif

/* What became of a shaded path (wp_shade_path). */
#define WP_SHADED_ENDS 0    /* missed, absorbed or out of roulette: finished */
#define WP_SHADED_GOES_ON 1 /* scattered: it traces its next ray */
#define WP_SHADED_CAPPED 2  /* cut at frame.max_depth: finished, and counted */

/* The random numbers of the bounce at slot's path vertex (wp_random_bounce_pairs),
 * for wp_shade_path. They depend on the path alone (its pixel, sample and
 * depth), not on what the ray hit, so a caller draws them before it has the
 * hit: with the Sobol sampler they are a chain of some 14 dependent 32-bit
 * multiplies (hundreds of cycles of latency on a CPU), which drawn where the
 * light sample waits for them stalled it (a third of the hexroom's shade).
 * Drawn early the processor overlaps them with other work: the fused
 * kernels draw them before the traversal; the shade kernel draws a whole
 * work-group's before a barrier, in a loop of their own where consecutive
 * work-items' chains overlap in part (docs/performance.md, issue #34's
 * "shade's random numbers drawn first"). WP_COMPUTED_HERE (rng.h) keeps the
 * compiler from sinking them back to their first use. */
static inline WP_ALWAYS_INLINE void wp_shade_numbers(WpFrame frame,
                                                     __global const wp_uint* path_pixel,
                                                     __global const wp_uint* path_sample,
                                                     __global const wp_uint* path_depth,
                                                     wp_uint slot, float4* first, float4* second) {
    wp_random_bounce_pairs(frame.seed, path_pixel[slot], path_sample[slot], path_depth[slot], first,
                           second);
}

/* Shade's work for one path: slot's ray hit `primitive` at distance t, and
 * `first` and `second` are its bounce's numbers (wp_shade_numbers; a ray
 * that missed reads none), by value: a pointer to them would keep them in
 * memory where the call is not inlined (the GPU targets' private memory).
 * Updates the slot's path state, leaves the shadow ray it made (if any) in
 * *shadow, and says what became of the path (WP_SHADED_*). It bumps no
 * counter and pushes onto no queue, so that the caller can do both for a
 * whole work-group at once (the shade kernel below). */
static inline int wp_shade_path(WP_STAGE_PARAMETERS, wp_uint slot, wp_uint primitive, float t,
                                float4 first, float4 second, WpShadowRay* shadow) {
    shadow->made = 0;
#if WP_MIRROR_NEE
    shadow->mirror_made = 0;
#endif
    if (primitive == WP_NO_HIT) { /* the ray left the scene: the path ends with what it has */
#if WP_HAS_ENVIRONMENT
        /* ... and the environment's radiance (emitters[0], if any), weighed
         * after a non-delta bounce against the light sample that could have
         * found the same direction (wp_sample_emitter's pdf). */
        wp_uint escaped_flags = path_flags[slot];
        if (frame.emitter_count > 0u && WP_PATH_EMISSION_SELECTED(frame.path_types, escaped_flags))
            radiance[slot] =
                (float4)(radiance[slot].xyz +
                             wp_shade_environment(&emitters[0], environment_cdf, texels,
                                                  ray_direction[slot].xyz, escaped_flags,
                                                  mirror_vertex[slot].w, throughput[slot].xyz),
                         0.0f);
#endif
        return WP_SHADED_ENDS;
    }

    wp_uint depth = path_depth[slot];
    WpPathRandom random;
    random.seed = frame.seed;
    random.pixel = path_pixel[slot];
    random.sample = path_sample[slot];
    random.depth = depth;
    wp_bounce_numbers(first, second, random.numbers);

    WP_SCENE_VIEW(scene);
    float3 direction = ray_direction[slot].xyz;
    WpSurface surface;
    wp_surface_at(&scene, primitive, ray_origin[slot].xyz, direction, t, &surface);
    WpMaterial material = materials[surface.material];
#if WP_HAS_TEXTURES
    if (wp_material_textured(&material))
        wp_apply_textures(&scene, wp_surface_uv(&scene, primitive, &surface), &material);
#endif
#if WP_AOV
    if (path_depth[slot] == 0u) /* the camera ray's first hit */
        wp_shade_aovs(&material, &surface, t, path_pixel[slot], aov_albedo, aov_normal, aov_depth);
#endif
    if (surface.inside_solid && !wp_bsdf_transmits(&material)) {
        /* Into a solid that transmits nothing only an offset origin can get:
         * inside a mirror sphere such a path would bounce until the depth
         * cap; absorb it instead. */
        return WP_SHADED_ENDS;
    }
    /* The geometric and the shading normal on the side the ray came from, and
     * where rays leave by that side. */
    float3 normal = surface.front_face ? surface.normal : -surface.normal;
    float3 spawn = surface.front_face ? surface.spawn_front : surface.spawn_back;
    /* What the BSDF sees of the surface (bsdf/interface.h). */
    WpShadingPoint point;
    point.n = surface.front_face ? surface.shading_normal : -surface.shading_normal;
    point.front_face = surface.front_face;
#if WP_HAS_ANISOTROPY /* alpha_u's direction (bsdf/frame.h) */
    wp_shading_tangent(surface.dp_du, &point);
#endif

    float3 beta = throughput[slot].xyz;
    float eta_squared = throughput[slot].w; /* the roulette's (WP_ROULETTE_RULE) */
    wp_uint flags = path_flags[slot];

    /* Step 1 only where the material emits: a surface that emits nothing
     * adds beta x 0 to the radiance, so the emission's weight (a light
     * density: four divisions and two square roots) and the radiance's store
     * would be made for nothing at the most common hit of all, a wall after
     * a diffuse bounce. */
    if (wp_material_emits(&material)) {
        float3 beta_emission = beta;
#if WP_HAS_WEIGHED_VERTICES && WP_HAS_LIGHTS && WP_USE_NEE
        /* After a weighed bounce from mirror_vertex (WP_PATH_GLOSSY): weighed
         * against the light sample there: an emissive triangle here, a sphere
         * below. */
        if ((flags & WP_PATH_GLOSSY) && surface.front_face &&
            wp_primitive_kind(&scene, primitive) == WP_PRIMITIVE_TRIANGLE) {
            float4 vertex = mirror_vertex[slot];
            WpTriangle light = scene.triangles[primitive];
            float light_pdf = wp_light_pdf(&scene, &light, vertex.xyz, surface.position);
#if WP_HAS_EMITTERS /* the triangles are chosen with this probability (lights.h) */
            light_pdf *= 1.0f - scene.emitter_pick;
#endif
            beta_emission *= wp_mis_bsdf_hit(vertex.w, light_pdf);
        }
#endif
#if WP_HAS_WEIGHED_VERTICES && WP_HAS_SPHERE_LIGHT && WP_USE_NEE
        /* ... and on an emitting sphere, against its cone sample there. */
        if ((flags & WP_PATH_GLOSSY) && surface.front_face &&
            wp_primitive_kind(&scene, primitive) == WP_PRIMITIVE_SPHERE)
            beta_emission *=
                wp_mis_bsdf_hit(mirror_vertex[slot].w,
                                wp_sphere_light_pick_pdf(&scene, primitive - scene.triangle_count,
                                                         mirror_vertex[slot].xyz));
#endif
#if WP_MIRROR_NEE /* weighed against the mirrored light sample (mirror_light.h) */
        if (flags & (WP_PATH_PLANAR_MIRROR | WP_PATH_SPHERE_MIRROR))
            beta_emission *=
                wp_mirror_emission_weight(&scene, primitive, flags, mirror_vertex[slot],
                                          ray_origin[slot].xyz, t, &surface, direction);
#endif
        radiance[slot] = (float4)(wp_shade_emission(&material, &surface, frame.path_types, flags,
                                                    beta_emission, radiance[slot].xyz),
                                  0.0f);
    }
    if (wp_bsdf_is_black(&material))
        return WP_SHADED_ENDS;
#if WP_PATH_LENGTH
    /* Mitsuba's max_depth: a light sample or a bounce from the last vertex
     * would make a path one edge longer than Mitsuba's longest. */
    if (depth >= frame.max_depth)
        return WP_SHADED_ENDS;
#endif

    /* Shadow rays and reflected rays leave by the side the ray came from,
     * transmitted ones (and shadow rays towards lights behind a surface that
     * transmits) by the other. */
    float3 origin = wp_offset_ray_origin(spawn, normal, surface.scale);
    float3 origin_behind = origin;
    if (wp_bsdf_transmits(&material))
        origin_behind = wp_offset_ray_origin(
            surface.front_face ? surface.spawn_back : surface.spawn_front, -normal, surface.scale);
#if (WP_HAS_LIGHTS || WP_HAS_EMITTERS) && WP_USE_NEE
    if (!wp_bsdf_is_delta(&material)) {
        /* One light point's numbers serve the light seen directly and, with
         * WP_MIRROR_NEE, by way of a planar mirror (two legs). */
        float u_pick = wp_path_random(&random, WP_DIM_LIGHT_PICK);
        float u_light = wp_path_random(&random, WP_DIM_LIGHT_U);
        float v_light = wp_path_random(&random, WP_DIM_LIGHT_V);
        if (WP_PATH_NEXT_EVENT_SELECTED(frame.path_types, flags))
            wp_shade_next_event(&scene, &material, &surface, direction, &point, origin,
                                origin_behind, beta, u_pick, u_light, v_light, shadow);
#if WP_MIRROR_NEE
        /* Its two legs make a path two edges longer than this vertex's,
         * which under Mitsuba's max_depth must fit. (An #if, not a constant
         * operand: clang's GPU targets warn about `!0 || ...`.) */
        shadow->mirror_made =
            WP_MIRROR_NEXT_EVENT_SELECTED(frame.path_types, flags) &&
#if WP_PATH_LENGTH
            depth + 1u < frame.max_depth &&
#endif
            wp_mirror_next_event(&scene, &material, &surface, direction, &point, origin, beta,
                                 u_pick, u_light, v_light, &shadow->mirror);
#endif
    }
#endif

    float u1 = wp_path_random(&random, WP_DIM_BSDF_U);
    float u2 = wp_path_random(&random, WP_DIM_BSDF_V);
    float u_lobe =
        wp_bsdf_samples_lobe(&material) ? wp_path_random(&random, WP_DIM_BSDF_LOBE) : 0.0f;
    WpBsdfSample scattered;
    wp_bsdf_sample(&material, direction, &point, u1, u2, u_lobe, &scattered);
    /* Nothing sampled, or a direction on the other side of the true surface
     * than the sample's flags say (by the shading normal): absorbed. */
    int transmitted = (scattered.flags & WP_BSDF_TRANSMISSION) != 0u;
    float cos_geometric = dot(scattered.direction, normal);
    if (scattered.flags == 0u || !(transmitted ? cos_geometric < 0.0f : cos_geometric > 0.0f))
        return WP_SHADED_ENDS;
    if (transmitted) /* the new ray leaves by the other side */
        origin = origin_behind;
    int delta = wp_bsdf_sample_is_delta(&scattered);
/* What the emission weight at the next vertex (or the escape) needs. */
#if WP_MIRROR_NEE || WP_HAS_WEIGHED_VERTICES || WP_HAS_ENVIRONMENT
    if (!delta)
        mirror_vertex[slot] = (float4)(surface.position, scattered.pdf);
#endif
#if WP_MIRROR_NEE
    flags = wp_mirror_flags_after(&scene, flags, primitive, &surface,
                                  material.kind == WP_MATERIAL_MIRROR);
#endif
    if (delta)
        flags |= WP_PATH_SPECULAR;
    else
        flags &= ~WP_PATH_SPECULAR;
    /* Emission that a non-delta sample finds is weighed against the light
     * sample made here wherever that one was weighed by MIS: a property of
     * the material, not of the lobe sampled (roughplastic's diffuse lobe
     * is part of the density MIS used; keyed on the glossy flag, its hits
     * were dropped and the image came out 0.3 % dark). */
    if (!delta && wp_bsdf_weighs_light(&material))
        flags |= WP_PATH_GLOSSY;
    else
        flags &= ~WP_PATH_GLOSSY;
#if WP_PATH_TYPES
    flags = wp_path_flags_after(flags, delta);
#endif

    float survival;
    if (!wp_shade_roulette(&material, &scattered, &random, u1, &beta, &eta_squared, &survival))
        return WP_SHADED_ENDS;
    if (depth + 1u > frame.max_depth)
        return WP_SHADED_CAPPED;
    throughput[slot] = (float4)(beta / survival, eta_squared);
    ray_origin[slot] = (float4)(origin, 0.0f);
    ray_direction[slot] = (float4)(scattered.direction, 0.0f);
    path_depth[slot] = depth + 1u;
    path_flags[slot] = flags;
    return WP_SHADED_GOES_ON;
}

/* Where a shaded path goes next, one atomic per path (the fused kernels):
 * onto the other ray queue if it goes on, else onto the finished queue. */
static inline void wp_queue_shaded_path(__global wp_uint* ray_queues,
                                        __global wp_uint* finished_queue,
                                        __global wp_uint* counters, WpFrame frame, WpLaunch launch,
                                        wp_uint slot, int outcome) {
    if (outcome == WP_SHADED_GOES_ON) {
        wp_queue_push(wp_ray_queue(ray_queues, frame, 1u - launch.ray_queue), counters,
                      1u - launch.ray_queue, slot);
        return;
    }
    if (outcome == WP_SHADED_CAPPED)
        atomic_inc(&counters[WP_COUNTER_CAPPED]);
    wp_queue_push(finished_queue, counters, WP_COUNTER_FINISHED, slot);
}

/* The queues a shaded path is pushed onto, as bits of one word. */
#define WP_PUSH_NEXT_RAY 1u      /* the other ray queue */
#define WP_PUSH_FINISHED 2u      /* the finished queue */
#define WP_PUSH_SHADOW 4u        /* the shadow queue */
#define WP_PUSH_MIRROR_SHADOW 8u /* the mirror queue (two-leg shadow rays) */
#define WP_PUSH_CAPPED 16u       /* counted as cut by the depth cap (no queue) */

/* How many queue entries ahead shade asks for a path's state. The queue's
 * slots are scattered over the pool, and on a CPU device a work-group's items
 * run one after the other: the loads of the slot's state, each in its own
 * buffer, stalled the kernel (the hexroom's largest sample counts sat right
 * after them). A few entries ahead, a few hundred cycles of shading, is
 * enough to hide them. */
#define WP_SHADE_LOOKAHEAD 4u

/* The slot at `index` of the ray queue as intersect left it, or of the queue
 * sorted by material (shade_sort.cl). */
static inline wp_uint wp_shade_queue_entry(__global const wp_uint* shade_order,
                                           __global wp_uint* ray_queues, WpFrame frame,
                                           WpLaunch launch, wp_uint index) {
    return launch.sorted ? shade_order[index]
                         : wp_ray_queue(ray_queues, frame, launch.ray_queue)[index];
}

/* Shade kernel: one work-item per queued ray.
 *
 * Its queue pushes are compacted per work-group instead of taking one global
 * atomic each: every work-item shades its path and says in pushes[] which
 * queues it joins; work-item 0 numbers them within the group and reserves
 * each queue's range with one atomic_add; then every work-item writes its
 * slot at its place. Besides saving the atomics this keeps them out of the
 * shading's work-item loop (PoCL splits the kernel into one loop per region
 * between barriers, and an atomic stops its vectoriser; on PoCL 3.1 the
 * float3 code still does, docs/profiling.md "Vectorising shade").
 * Before the shading, a region of its own draws the work-items' random
 * numbers (wp_shade_numbers).
 * Surplus work-items (past the queue's end) shade nothing and push nothing,
 * but reach the barriers like the rest. Which place a slot takes in a queue
 * changes nothing that is computed: every slot owns its own pixels. */
__kernel void shade(WP_STAGE_PARAMETERS) {
    __local wp_uint pushes[WP_MAX_WORK_GROUP_SIZE];
    __local wp_uint path_place[WP_MAX_WORK_GROUP_SIZE]; /* in the next-ray or finished queue */
    __local wp_uint shadow_place[WP_MAX_WORK_GROUP_SIZE];
    __local wp_uint mirror_place[WP_MAX_WORK_GROUP_SIZE];
    __local wp_uint first_place[4]; /* next ray, finished, shadow, mirror */

    wp_uint index = get_global_id(0);
    wp_uint item = get_local_id(0);
    wp_uint slot = 0u, push = 0u, primitive = WP_NO_HIT;
    wp_uint queued = counters[launch.ray_queue];
    /* First the group's random numbers, each work-item's for its own path
     * (wp_shade_numbers), alone in this region: the loop PoCL makes of it
     * runs the chains back to back, and the processor overlaps them in part.
     * Not for rays that missed (they read none). */
    float4 first = (float4)(0.0f), second = (float4)(0.0f);
    if (index < queued) {
        slot = wp_shade_queue_entry(shade_order, ray_queues, frame, launch, index);
        primitive = hit_primitive[slot];
        if (primitive != WP_NO_HIT)
            wp_shade_numbers(frame, path_pixel, path_sample, path_depth, slot, &first, &second);
    }
    barrier(CLK_LOCAL_MEM_FENCE);

    if (index < queued) {
        if (index + WP_SHADE_LOOKAHEAD < queued) {
            wp_uint ahead = wp_shade_queue_entry(shade_order, ray_queues, frame, launch,
                                                 index + WP_SHADE_LOOKAHEAD);
            WP_PREFETCH_LINE(hit_primitive + ahead);
            WP_PREFETCH_LINE(hit_t + ahead);
            WP_PREFETCH_LINE(ray_origin + ahead);
            WP_PREFETCH_LINE(ray_direction + ahead);
            WP_PREFETCH_LINE(throughput + ahead);
            WP_PREFETCH_LINE(path_depth + ahead);
            WP_PREFETCH_LINE(path_flags + ahead);
            WP_PREFETCH_LINE(path_pixel + ahead);
            WP_PREFETCH_LINE(path_sample + ahead);
            WP_PREFETCH_LINE_FOR_WRITE(shadow_origin + ahead);
            WP_PREFETCH_LINE_FOR_WRITE(shadow_direction + ahead);
            WP_PREFETCH_LINE_FOR_WRITE(shadow_contribution + ahead);
            WP_PREFETCH_LINE_FOR_WRITE(mirror_vertex + ahead);
        }
        WpShadowRay shadow;
        int outcome =
            wp_shade_path(WP_STAGE_ARGUMENTS, slot, primitive,
                          primitive == WP_NO_HIT ? 0.0f : hit_t[slot], first, second, &shadow);
        push = outcome == WP_SHADED_GOES_ON ? WP_PUSH_NEXT_RAY : WP_PUSH_FINISHED;
        if (outcome == WP_SHADED_CAPPED)
            push |= WP_PUSH_CAPPED;
        if (shadow.made) {
            push |= WP_PUSH_SHADOW;
            shadow_origin[slot] = (float4)(shadow.origin, 0.0f);
            shadow_direction[slot] = (float4)(shadow.direction, shadow.length);
            shadow_contribution[slot] = (float4)(shadow.contribution, 0.0f);
        }
#if WP_MIRROR_NEE /* the two-leg ray goes to the mirror queue (shadow.cl, mirror_shadow) */
        if (shadow.mirror_made) {
            push |= WP_PUSH_MIRROR_SHADOW;
            mirror_shadow_origin[slot] = shadow.mirror.origin;
            mirror_shadow_direction[slot] = shadow.mirror.direction;
            mirror_shadow_origin2[slot] = shadow.mirror.origin2;
            mirror_shadow_direction2[slot] = shadow.mirror.direction2;
            mirror_shadow_contribution[slot] = shadow.mirror.contribution;
        }
#endif
    }
    pushes[item] = push;
    barrier(CLK_LOCAL_MEM_FENCE);

    if (item == 0u) {
        wp_uint next_rays = 0u, finished = 0u, shadows = 0u, mirrors = 0u, capped = 0u;
        for (wp_uint i = 0u; i < get_local_size(0); ++i) {
            wp_uint p = pushes[i];
            path_place[i] = (p & WP_PUSH_NEXT_RAY) ? next_rays : finished;
            next_rays += p & WP_PUSH_NEXT_RAY ? 1u : 0u;
            finished += p & WP_PUSH_FINISHED ? 1u : 0u;
            shadow_place[i] = shadows;
            shadows += p & WP_PUSH_SHADOW ? 1u : 0u;
            mirror_place[i] = mirrors;
            mirrors += p & WP_PUSH_MIRROR_SHADOW ? 1u : 0u;
            capped += p & WP_PUSH_CAPPED ? 1u : 0u;
        }
        first_place[0] = next_rays ? atomic_add(&counters[1u - launch.ray_queue], next_rays) : 0u;
        first_place[1] = finished ? atomic_add(&counters[WP_COUNTER_FINISHED], finished) : 0u;
        first_place[2] = shadows ? atomic_add(&counters[WP_COUNTER_SHADOW_RAYS], shadows) : 0u;
        first_place[3] =
            mirrors ? atomic_add(&counters[WP_COUNTER_MIRROR_SHADOW_RAYS], mirrors) : 0u;
        if (capped)
            atomic_add(&counters[WP_COUNTER_CAPPED], capped);
    }
    barrier(CLK_LOCAL_MEM_FENCE);

    wp_uint next_place = first_place[0] + path_place[item];
    wp_uint finished_place = first_place[1] + path_place[item];
    wp_uint shadow_ray_place = first_place[2] + shadow_place[item];
    wp_uint mirror_ray_place = frame.pool_size + first_place[3] + mirror_place[item];
    if (push & WP_PUSH_NEXT_RAY)
        wp_ray_queue(ray_queues, frame, 1u - launch.ray_queue)[next_place] = slot;
    if (push & WP_PUSH_FINISHED)
        finished_queue[finished_place] = slot;
    if (push & WP_PUSH_SHADOW)
        shadow_queue[shadow_ray_place] = slot;
    if (push & WP_PUSH_MIRROR_SHADOW) /* the mirror queue follows the shadow queue */
        shadow_queue[mirror_ray_place] = slot;
}
