/* The scene features a program is compiled for.
 *
 * The host derives them from the scene and passes -D options (see
 * src/render/device_scene.cpp (SceneFeatures::build_options)); code for an absent feature compiles
 * to nothing. Left undefined, a feature is on, which gives the general kernels.
 */
#ifndef WP_SCENE_FEATURES_H
#define WP_SCENE_FEATURES_H

#include "wp_shared.h"

#ifndef WP_HAS_TRIANGLES
#define WP_HAS_TRIANGLES 1
#endif
#ifndef WP_HAS_SPHERES
#define WP_HAS_SPHERES 1
#endif
#ifndef WP_HAS_DIFFUSE
#define WP_HAS_DIFFUSE 1
#endif
/* Material kinds in use: one WP_HAS_KIND per kind with a BSDF (the bsdf
 * column of WP_MATERIALS, wp_shared.h; the check below fails to compile when
 * a row has no default here). */
#ifndef WP_HAS_MIRROR
#define WP_HAS_MIRROR 1
#endif
#ifndef WP_HAS_CONDUCTOR
#define WP_HAS_CONDUCTOR 1
#endif
#ifndef WP_HAS_ROUGHCONDUCTOR
#define WP_HAS_ROUGHCONDUCTOR 1
#endif
#ifndef WP_HAS_DIELECTRIC
#define WP_HAS_DIELECTRIC 1
#endif
#ifndef WP_HAS_THINDIELECTRIC
#define WP_HAS_THINDIELECTRIC 1
#endif
#ifndef WP_HAS_PLASTIC
#define WP_HAS_PLASTIC 1
#endif
#ifndef WP_HAS_ROUGHDIELECTRIC
#define WP_HAS_ROUGHDIELECTRIC 1
#endif
#ifndef WP_HAS_ROUGHPLASTIC
#define WP_HAS_ROUGHPLASTIC 1
#endif
#define WP_MATERIAL_FEATURE_CHECK(KIND, Name, name, value, bsdf, glossy)                           \
    WP_IF(bsdf)(wp_has_##name##_is_defined = WP_HAS_##KIND, )
enum { WP_MATERIALS(WP_MATERIAL_FEATURE_CHECK) wp_material_features_checked };
#undef WP_MATERIAL_FEATURE_CHECK
/* The camera's: a thin lens (aperture radius > 0), and one switch per
 * pixel filter with sampling code of its own (the sampled column of
 * WP_FILTERS, wp_shared.h; checked like the materials'). */
#ifndef WP_HAS_LENS
#define WP_HAS_LENS 1
#endif
#ifndef WP_HAS_TENT_FILTER
#define WP_HAS_TENT_FILTER 1
#endif
#ifndef WP_HAS_GAUSSIAN_FILTER
#define WP_HAS_GAUSSIAN_FILTER 1
#endif
#define WP_FILTER_FEATURE_CHECK(KIND, Name, name, value, sampled)                                  \
    WP_IF(sampled)(wp_has_##name##_filter_is_defined = WP_HAS_##KIND##_FILTER, )
enum { WP_FILTERS(WP_FILTER_FEATURE_CHECK) wp_filter_features_checked };
#undef WP_FILTER_FEATURE_CHECK
/* Textures in use: one switch per kind (the rows of WP_TEXTURES, wp_shared.h;
 * checked like the materials'). WP_HAS_TEXTURES, any of them, brings in the
 * texture coordinates of the hit point (primitive.h). */
#ifndef WP_HAS_BITMAP_TEXTURE
#define WP_HAS_BITMAP_TEXTURE 1
#endif
#ifndef WP_HAS_CHECKERBOARD_TEXTURE
#define WP_HAS_CHECKERBOARD_TEXTURE 1
#endif
#define WP_TEXTURE_FEATURE_CHECK(KIND, Name, name, value)                                          \
    wp_has_##name##_texture_is_defined = WP_HAS_##KIND##_TEXTURE,
enum { WP_TEXTURES(WP_TEXTURE_FEATURE_CHECK) wp_texture_features_checked };
#undef WP_TEXTURE_FEATURE_CHECK
#define WP_TEXTURE_FEATURE_TERM(KIND, Name, name, value) || WP_HAS_##KIND##_TEXTURE
#define WP_HAS_TEXTURES (0 WP_TEXTURES(WP_TEXTURE_FEATURE_TERM))
/* Anisotropic roughness (alpha_u != alpha_v, or two different textures):
 * the surface record carries the tangent dp/du that alpha_u runs along
 * (tangent.h, bsdf/frame.h). */
#ifndef WP_HAS_ANISOTROPY
#define WP_HAS_ANISOTROPY 1
#endif
#ifndef WP_HAS_SHADING_NORMALS /* triangles with vertex normals */
#define WP_HAS_SHADING_NORMALS 1
#endif
#ifndef WP_HAS_LIGHTS /* emissive triangles to sample by next-event estimation */
#define WP_HAS_LIGHTS 1
#endif
/* The emissive triangles picked by power (area times luminance) rather than by
 * area: on only where their luminances differ (src/render/light_pick.hpp), so
 * that a scene whose lights all have one radiance keeps the area pick's code. */
#ifndef WP_HAS_POWER_LIGHT_PICK
#define WP_HAS_POWER_LIGHT_PICK 1
#endif
/* The emitters that are not surfaces (WpEmitter, wp_shared.h), one switch
 * per kind, on when the scene has one; WP_HAS_EMITTERS, any of them, compiles
 * the choice between them and the emissive triangles (lights.h). */
#ifndef WP_HAS_POINT_LIGHT
#define WP_HAS_POINT_LIGHT 1
#endif
#ifndef WP_HAS_SPOT_LIGHT
#define WP_HAS_SPOT_LIGHT 1
#endif
#ifndef WP_HAS_DIRECTIONAL_LIGHT
#define WP_HAS_DIRECTIONAL_LIGHT 1
#endif
#ifndef WP_HAS_CONSTANT_LIGHT
#define WP_HAS_CONSTANT_LIGHT 1
#endif
#ifndef WP_HAS_ENVMAP_LIGHT
#define WP_HAS_ENVMAP_LIGHT 1
#endif
#ifndef WP_HAS_SPHERE_LIGHT /* spheres of an emissive material (lights/sphere.h) */
#define WP_HAS_SPHERE_LIGHT 1
#endif
#define WP_HAS_EMITTERS                                                                            \
    (WP_HAS_POINT_LIGHT || WP_HAS_SPOT_LIGHT || WP_HAS_DIRECTIONAL_LIGHT ||                        \
     WP_HAS_CONSTANT_LIGHT || WP_HAS_ENVMAP_LIGHT || WP_HAS_SPHERE_LIGHT)
/* An environment (constant or envmap): what a ray that escapes finds, and a
 * light that a BSDF sample can find from any vertex, so its light samples are
 * weighed by multiple importance sampling everywhere (shade.cl). */
#define WP_HAS_ENVIRONMENT (WP_HAS_CONSTANT_LIGHT || WP_HAS_ENVMAP_LIGHT)
#ifndef WP_HAS_PLANAR_MIRRORS /* flat mirror triangles and lights (kernels/mirror_light.h) */
#define WP_HAS_PLANAR_MIRRORS 1
#endif
#ifndef WP_HAS_MIRROR_SPHERES /* mirror spheres and lights (kernels/mirror_light.h) */
#define WP_HAS_MIRROR_SPHERES 1
#endif
/* Instances of shape groups (kernels/instance.h): a two-level hierarchy, the
 * instances' meshes traversed in their object space. Only with WP_USE_BVH. */
#ifndef WP_HAS_INSTANCES
#define WP_HAS_INSTANCES 1
#endif

/* Acceleration switch, not a scene feature: traverse a bounding volume
 * hierarchy (bvh.h) instead of testing every primitive. The host turns it on
 * for scenes past the fixed-count limit (src/render/device_scene.hpp) and
 * uploads the hierarchy; left undefined it is off, so that test kernels built
 * without options need no hierarchy. */
#ifndef WP_USE_BVH
#define WP_USE_BVH 0
#endif
/* Instances are reached only through the hierarchy (the host builds one for
 * every scene that has them). */
#define WP_TRACE_INSTANCES (WP_HAS_INSTANCES && WP_USE_BVH)

/* The shadow terminator fix of shading normals (primitive.h): on unless a test
 * turns it off to show what it fixes. */
#ifndef WP_SHADOW_TERMINATOR_FIX
#define WP_SHADOW_TERMINATOR_FIX 1
#endif

/* Output switch, not a scene feature: shade adds the camera ray's first hit
 * to the AOV buffers (albedo, shading normal, depth; kernels/shade.cl). The
 * host turns it on only for a render that asks for AOVs (--aov); off, no AOV
 * code is compiled and images are as without it. */
#ifndef WP_AOV
#define WP_AOV 0
#endif

/* Estimator switch, not a scene feature: with next-event estimation off,
 * light is found only by paths that hit an emitter, and emitters count after
 * every bounce. Slower to converge, but with bounded variance (no 1/r^2). */
#ifndef WP_USE_NEE
#define WP_USE_NEE 1
#endif

#endif /* WP_SCENE_FEATURES_H */
