/* Stage 3, shade: what happens where each queued ray hit.
 *
 *  1. Emission: an emitter's front face adds throughput x radiance, but only
 *     for camera rays and rays after a mirror bounce. After a diffuse bounce
 *     the light was already counted by next-event estimation, and counting it
 *     again would count it twice.
 *     (With WP_USE_NEE=0 there is no step 2 and emitters count after every
 *     bounce.)
 *  2. Next-event estimation (diffuse surfaces): pick a point uniformly by area
 *     on the emissive triangles and queue one shadow ray carrying the
 *     contribution it would make if nothing blocks it.
 *  3. Scattering: a cosine-weighted direction for Lambertian surfaces
 *     (throughput x reflectance, as cos/pdf cancels against 1/pi), the exact
 *     reflection for mirrors (throughput x reflectance).
 *  4. Russian roulette: survive with probability min(1, max(throughput)) and
 *     divide survivors' throughput by it, which keeps the estimate unbiased.
 *     Past frame.max_depth bounces a path is cut and counted; the cap is a
 *     guard against endless mirror corridors, not part of the estimator.
 *
 * Survivors are pushed to the next ray queue with one atomic per item.
 */
#include "material.h"
#include "rng.h"
#include "sampling.h"
#include "traverse.h"

/* Shadow rays stop this many offsets short of the light point, so the light
 * itself is never taken for an occluder. */
#define WP_SHADOW_END_MARGIN 4.0f

/* The first light whose cumulative area fraction exceeds u. */
static inline wp_uint wp_pick_light(__global const WpLight* lights, wp_uint count, float u) {
    wp_uint low = 0, high = count - 1;
    while (low < high) {
        wp_uint mid = (low + high) / 2;
        if (lights[mid].cdf > u)
            high = mid;
        else
            low = mid + 1;
    }
    return low;
}

__kernel void shade(WpFrame frame, wp_uint ray_count, __global const wp_uint* ray_queue,
                    __global float4* ray_origin, __global float4* ray_direction,
                    __global const float* hit_t, __global const wp_uint* hit_primitive,
                    __global float4* throughput, __global float4* radiance,
                    __global wp_uint* path_depth, __global wp_uint* path_flags,
                    __global const wp_uint* path_pixel, __global const WpTriangle* triangles,
                    __global const WpSphere* spheres, __global const WpMaterial* materials,
                    __global const WpLight* lights, __global wp_uint* next_queue,
                    __global wp_uint* shadow_queue, __global float4* shadow_origin,
                    __global float4* shadow_direction, __global float4* shadow_contribution,
                    __global wp_uint* counters) {
    wp_uint index = get_global_id(0);
    if (index >= ray_count)
        return;
    wp_uint slot = ray_queue[index];
    wp_uint primitive = hit_primitive[slot];
    if (primitive == WP_NO_HIT)
        return; /* the ray left the scene: the path ends with what it has */

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

    if ((!WP_USE_NEE || (flags & WP_PATH_SPECULAR)) && front_face)
        sum += beta * material.emission.xyz;
    if (material.kind == WP_MATERIAL_EMITTER) {
        radiance[slot] = (float4)(sum, 0.0f);
        return;
    }

    float3 origin = wp_offset_ray_origin(position, facing_normal, scale);
    float3 reflectance = material.reflectance.xyz;
    float3 next_direction;
#if WP_HAS_MIRROR
    if (material.kind == WP_MATERIAL_MIRROR) {
        next_direction = wp_reflect(direction, facing_normal);
        flags |= WP_PATH_SPECULAR;
    } else
#endif
    {
#if WP_HAS_LIGHTS && WP_USE_NEE
        if (frame.light_count > 0) { /* general kernels may meet a scene without lights */
            float u_pick =
                wp_random(frame.seed, pixel, frame.sample_index, depth, WP_DIM_LIGHT_PICK);
            float u_light = wp_random(frame.seed, pixel, frame.sample_index, depth, WP_DIM_LIGHT_U);
            float v_light = wp_random(frame.seed, pixel, frame.sample_index, depth, WP_DIM_LIGHT_V);
            WpTriangle light =
                triangles[lights[wp_pick_light(lights, frame.light_count, u_pick)].triangle];
            float3 light_point =
                wp_sample_triangle(light.v0.xyz, light.v1.xyz, light.v2.xyz, u_light, v_light);
            float3 light_normal = normalize(wp_triangle_normal(&light));
            float3 to_light = light_point - origin;
            float distance = length(to_light);
            float3 wi = to_light / distance;
            float cos_surface = dot(facing_normal, wi);
            float cos_light = -dot(light_normal, wi);
            float length_to_test =
                distance -
                WP_SHADOW_END_MARGIN * wp_offset_distance(light_point, wp_triangle_scale(&light));
            if (cos_surface > 0.0f && cos_light > 0.0f && length_to_test > 0.0f) {
                float3 emitted = materials[light.material].emission.xyz;
                float geometry = cos_surface * cos_light / (distance * distance);
                float3 contribution =
                    beta * reflectance * emitted * (geometry * frame.light_area / WP_PI);
                if (!wp_is_black(contribution)) {
                    wp_uint entry = atomic_inc(&counters[WP_COUNTER_SHADOW_RAYS]);
                    shadow_queue[entry] = slot;
                    shadow_origin[slot] = (float4)(origin, 0.0f);
                    shadow_direction[slot] = (float4)(wi, length_to_test);
                    shadow_contribution[slot] = (float4)(contribution, 0.0f);
                }
            }
        }
#endif
        float u1 = wp_random(frame.seed, pixel, frame.sample_index, depth, WP_DIM_BSDF_U);
        float u2 = wp_random(frame.seed, pixel, frame.sample_index, depth, WP_DIM_BSDF_V);
        next_direction = wp_sample_cosine_hemisphere(facing_normal, u1, u2);
        flags &= ~WP_PATH_SPECULAR;
    }
    beta *= reflectance;

    float survival = fmin(1.0f, wp_max_component(beta));
    float u_roulette = wp_random(frame.seed, pixel, frame.sample_index, depth, WP_DIM_ROULETTE);
    radiance[slot] = (float4)(sum, 0.0f);
    if (u_roulette >= survival)
        return;
    if (depth + 1u > frame.max_depth) {
        atomic_inc(&counters[WP_COUNTER_CAPPED]);
        return;
    }
    throughput[slot] = (float4)(beta / survival, 0.0f);
    ray_origin[slot] = (float4)(origin, 0.0f);
    ray_direction[slot] = (float4)(next_direction, 0.0f);
    path_depth[slot] = depth + 1u;
    path_flags[slot] = flags;
    next_queue[atomic_inc(&counters[WP_COUNTER_NEXT_RAYS])] = slot;
}
