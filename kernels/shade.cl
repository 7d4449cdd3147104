/* Stage 3, shade: what happens where each queued ray hit.
 *
 *  1. Emission: an emitter's front face adds throughput x radiance, but only
 *     for camera rays and rays after a mirror bounce. After a diffuse bounce
 *     the light was already counted by next-event estimation, and counting it
 *     again would count it twice. (With WP_USE_NEE=0 there is no step 2 and
 *     emitters count after every bounce.)
 *  2. Next-event estimation (diffuse surfaces): sample a point on the lights
 *     (lights.h) and queue one shadow ray carrying the contribution it would
 *     make if nothing blocks it.
 *  3. Scattering: a cosine-weighted direction for Lambertian surfaces
 *     (throughput x reflectance, as cos/pdf cancels against 1/pi), the exact
 *     reflection for mirrors (throughput x reflectance).
 *  4. Russian roulette: survive with probability min(1, max(throughput)) and
 *     divide survivors' throughput by it, which keeps the estimate unbiased.
 *     Past frame.max_depth bounces a path is cut and counted; the cap is a
 *     guard against endless mirror corridors, not part of the estimator.
 *  With WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT, steps 3 and 4 are the
 *  report's estimator instead: uniform (theta, phi) directions weighted by
 *  pi rho cos sin, and its albedo ("angle") roulette (estimator.h).
 *
 * Survivors go to the next ray queue, finished paths (missed, absorbed, cut)
 * to the finished queue, each with one atomic per item.
 */
#include "estimator.h"
#include "lights.h"
#include "material.h"
#include "rng.h"
#include "sampling.h"
#include "traverse.h"

__kernel void shade(WpFrame frame, __global const wp_uint* ray_queue, __global wp_uint* counters,
                    wp_uint ray_counter, __global wp_uint* next_queue, wp_uint next_counter,
                    __global wp_uint* finished_queue, __global float4* ray_origin,
                    __global float4* ray_direction, __global const float* hit_t,
                    __global const wp_uint* hit_primitive, __global float4* throughput,
                    __global float4* radiance, __global wp_uint* path_depth,
                    __global wp_uint* path_flags, __global const wp_uint* path_pixel,
                    __global const wp_uint* path_sample, __global const WpTriangle* triangles,
                    __global const WpSphere* spheres, __global const WpMaterial* materials,
                    __global const WpLight* lights, __global wp_uint* shadow_queue,
                    __global float4* shadow_origin, __global float4* shadow_direction,
                    __global float4* shadow_contribution) {
    wp_uint index = get_global_id(0);
    if (index >= counters[ray_counter])
        return;
    wp_uint slot = ray_queue[index];
    wp_uint primitive = hit_primitive[slot];
    if (primitive == WP_NO_HIT) { /* the ray left the scene: the path ends with what it has */
        finished_queue[atomic_inc(&counters[WP_COUNTER_FINISHED])] = slot;
        return;
    }

    float3 direction = ray_direction[slot].xyz;
    float3 position = ray_origin[slot].xyz + hit_t[slot] * direction;

    /* Geometric normal, and the hit point reprojected onto the surface: its
     * error then scales with the surface's coordinates, not with t. */
    float3 normal;
    float scale; /* magnitude of the primitive's coordinates, for ray offsets */
    wp_uint material_index;
#if WP_HAS_SPHERES
    if (primitive >= frame.triangle_count) {
        WpSphere sphere = spheres[primitive - frame.triangle_count];
        normal = normalize(position - sphere.center_radius.xyz);
        position = sphere.center_radius.xyz + sphere.center_radius.w * normal;
        scale = wp_sphere_scale(sphere.center_radius);
        material_index = sphere.material;
        if (dot(direction, normal) >= 0.0f) {
            /* Spheres are opaque solids: a ray meets one from inside only
             * when an offset origin landed inside it, next to a contact point
             * (docs/stability.md, case 4). Inside a mirror sphere such a path
             * would bounce until the depth cap; absorb it instead. */
            finished_queue[atomic_inc(&counters[WP_COUNTER_FINISHED])] = slot;
            return;
        }
    } else
#endif
    {
        WpTriangle triangle = triangles[primitive];
        normal = normalize(wp_triangle_normal(&triangle));
        position -= dot(position - triangle.v0.xyz, normal) * normal;
        scale = wp_triangle_scale(&triangle);
        material_index = triangle.material;
    }
    WpMaterial material = materials[material_index];
    int front_face = dot(direction, normal) < 0.0f;
    float3 facing_normal = front_face ? normal : -normal; /* on the side the ray came from */

    float3 beta = throughput[slot].xyz;
    float3 sum = radiance[slot].xyz;
    wp_uint depth = path_depth[slot];
    wp_uint flags = path_flags[slot];
    wp_uint pixel = path_pixel[slot];
    wp_uint sample = path_sample[slot];

    if ((!WP_USE_NEE || (flags & WP_PATH_SPECULAR)) && front_face)
        sum += beta * material.emission.xyz;
    radiance[slot] = (float4)(sum, 0.0f);
    if (material.kind == WP_MATERIAL_EMITTER) {
        finished_queue[atomic_inc(&counters[WP_COUNTER_FINISHED])] = slot;
        return;
    }

    float3 origin = wp_offset_ray_origin(position, facing_normal, scale);
    float3 reflectance = material.reflectance.xyz;
    float3 next_direction;
    float3 weight = reflectance; /* BRDF x cos / pdf of next_direction */
#if WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT
    /* decides the roulette: a fresh number for mirrors, theta's for diffuse */
    float u_survive = wp_random(frame.seed, pixel, sample, depth, WP_DIM_ROULETTE);
#endif
#if WP_HAS_MIRROR
    if (material.kind == WP_MATERIAL_MIRROR) {
        next_direction = wp_reflect(direction, facing_normal);
        flags |= WP_PATH_SPECULAR;
    } else
#endif
    {
#if WP_HAS_LIGHTS && WP_USE_NEE
        WpLightSample light;
        if (wp_sample_light(frame, triangles, materials, lights, position, origin, facing_normal,
                            wp_random(frame.seed, pixel, sample, depth, WP_DIM_LIGHT_PICK),
                            wp_random(frame.seed, pixel, sample, depth, WP_DIM_LIGHT_U),
                            wp_random(frame.seed, pixel, sample, depth, WP_DIM_LIGHT_V), &light)) {
            float3 contribution = beta * reflectance * light.irradiance * (1.0f / WP_PI);
            if (!wp_is_black(contribution)) {
                shadow_queue[atomic_inc(&counters[WP_COUNTER_SHADOW_RAYS])] = slot;
                shadow_origin[slot] = (float4)(origin, 0.0f);
                shadow_direction[slot] = (float4)(light.direction, light.length);
                shadow_contribution[slot] = (float4)(contribution, 0.0f);
            }
        }
#endif
        float u1 = wp_random(frame.seed, pixel, sample, depth, WP_DIM_BSDF_U);
        float u2 = wp_random(frame.seed, pixel, sample, depth, WP_DIM_BSDF_V);
#if WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT
        /* theta' = u1 pi/2; the roulette below ends the path when
         * theta' > sigma pi/2, i.e. u1 >= sigma; survivors go on at
         * theta = theta' / sigma, uniform in [0, pi/2] (estimator.h). */
        float sigma = fmin(1.0f, wp_max_component(reflectance));
        u_survive = u1;
        float theta = (sigma > 0.0f ? fmin(1.0f, u1 / sigma) : 0.0f) * (0.5f * WP_PI);
        next_direction = wp_direction_from_angles(facing_normal, theta, 2.0f * WP_PI * u2);
        weight = reflectance * (WP_PI * cos(theta) * sin(theta));
#else
        next_direction = wp_sample_cosine_hemisphere(facing_normal, u1, u2);
#endif
        flags &= ~WP_PATH_SPECULAR;
    }

#if WP_DIFFUSE_SAMPLING == WP_DIFFUSE_REPORT
    /* The report's roulette: survive with the surface's albedo sigma, whatever
     * the path carries; eq. 2.10 divides survivors by it. */
    float survival = fmin(1.0f, wp_max_component(reflectance));
    int survives = u_survive < survival;
    beta *= weight;
#else
    beta *= weight;
    float survival = fmin(1.0f, wp_max_component(beta));
    float u_roulette = wp_random(frame.seed, pixel, sample, depth, WP_DIM_ROULETTE);
    int survives = u_roulette < survival;
#endif
    if (survives && depth + 1u > frame.max_depth) {
        atomic_inc(&counters[WP_COUNTER_CAPPED]);
        survives = 0;
    }
    if (!survives) {
        finished_queue[atomic_inc(&counters[WP_COUNTER_FINISHED])] = slot;
        return;
    }
    throughput[slot] = (float4)(beta / survival, 0.0f);
    ray_origin[slot] = (float4)(origin, 0.0f);
    ray_direction[slot] = (float4)(next_direction, 0.0f);
    path_depth[slot] = depth + 1u;
    path_flags[slot] = flags;
    next_queue[atomic_inc(&counters[next_counter])] = slot;
}
