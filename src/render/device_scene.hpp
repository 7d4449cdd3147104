// The scene flattened into the float32 arrays the kernels read, and the
// features that decide which code the kernels are compiled with.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/light_pick.hpp"
#include "scene/bvh.hpp"
#include "scene/scene.hpp"
#include "wp_shared.h"

namespace wp {

// Scenes with at most this many primitives (triangles plus spheres) get
// kernels with the counts compiled in (see SceneFeatures::fixed_counts). The
// limit comes from measurement on PoCL: docs/specialization.md.
inline constexpr std::uint32_t kMaxFixedCountPrimitives = 64;
// Scenes with more primitives than this are traversed through a bounding
// volume hierarchy (SceneFeatures::bvh), fewer by testing every primitive.
inline constexpr std::uint32_t kMinBvhPrimitives = kMaxFixedCountPrimitives + 1;

// The feature switches, one row each: X(member, kernel switch). Each is a
// preprocessor switch of kernels/scene_features.h that compiles its code in
// or out; SceneFeatures has a bool per row, and its build options and
// description follow the rows (a new feature is a row here, its #ifndef in
// scene_features.h, and its line in analyse_features). The material kinds'
// rows come from WP_MATERIALS (kernels/wp_shared.h): one per kind with a
// BSDF, named as the kind, set when the scene uses the kind.
#define WP_MATERIAL_FEATURE_ROW(X, KIND, Name, name, value, bsdf, glossy)                          \
    WP_IF(bsdf)(X(name, WP_HAS_##KIND))
#define WP_MATERIAL_FEATURES(X) WP_MATERIALS_WITH(WP_MATERIAL_FEATURE_ROW, X)
// The pixel filters' rows come from WP_FILTERS: one per filter with sampling
// code (not the box), named NAME_filter, set when the camera uses it.
#define WP_FILTER_FEATURE_ROW(X, KIND, Name, name, value, sampled)                                 \
    WP_IF(sampled)(X(name##_filter, WP_HAS_##KIND##_FILTER))
#define WP_FILTER_FEATURES(X) WP_FILTERS_WITH(WP_FILTER_FEATURE_ROW, X)
// The textures' rows come from WP_TEXTURES: one per kind, named NAME_texture,
// set when a material uses one.
#define WP_TEXTURE_FEATURE_ROW(X, KIND, Name, name, value)                                         \
    X(name##_texture, WP_HAS_##KIND##_TEXTURE)
#define WP_TEXTURE_FEATURES(X) WP_TEXTURES_WITH(WP_TEXTURE_FEATURE_ROW, X)
#define WP_SCENE_FEATURES(X)                                                                       \
    X(triangles, WP_HAS_TRIANGLES)                                                                 \
    X(spheres, WP_HAS_SPHERES)                                                                     \
    WP_MATERIAL_FEATURES(X)                    /* material kinds in use */                         \
    X(shading_normals, WP_HAS_SHADING_NORMALS) /* triangles with vertex normals */                 \
    X(anisotropy, WP_HAS_ANISOTROPY)           /* alpha_u != alpha_v: the tangent, dp/du */        \
    X(lights, WP_HAS_LIGHTS)                   /* emissive triangles for next-event estimation */  \
    X(power_light_pick, WP_HAS_POWER_LIGHT_PICK) /* their radiances differ: picked by power */     \
    X(planar_mirrors, WP_HAS_PLANAR_MIRRORS)     /* flat mirror triangles, and lights */           \
    X(mirror_spheres, WP_HAS_MIRROR_SPHERES)     /* spheres of a mirror material, and lights */    \
    X(lens, WP_HAS_LENS)                         /* a thin lens: aperture radius > 0 */            \
    X(point_light, WP_HAS_POINT_LIGHT)           /* emitters by kind (Scene::emitters) */          \
    X(spot_light, WP_HAS_SPOT_LIGHT)                                                               \
    X(directional_light, WP_HAS_DIRECTIONAL_LIGHT)                                                 \
    X(constant_light, WP_HAS_CONSTANT_LIGHT)                                                       \
    X(envmap_light, WP_HAS_ENVMAP_LIGHT)                                                           \
    X(sphere_light, WP_HAS_SPHERE_LIGHT) /* spheres of an emissive material */                     \
    X(instances, WP_HAS_INSTANCES)       /* instances of shape groups (kernels/instance.h) */      \
    WP_FILTER_FEATURES(X)                /* the pixel filter, unless the box */                    \
    WP_TEXTURE_FEATURES(X)               /* texture kinds in use */

// Which kinds of primitive, material and light the scene uses.
struct SceneFeatures {
#define WP_FEATURE_MEMBER(member, kernel_switch) bool member = true;
    WP_SCENE_FEATURES(WP_FEATURE_MEMBER)
#undef WP_FEATURE_MEMBER
    // Small scenes: the primitive counts as compile-time constants
    // (-D WP_TRIANGLE_COUNT=n -D WP_SPHERE_COUNT=m), so the traversal loops of
    // kernels/traverse.h have fixed trip counts and unroll. A program built so
    // is only valid for scenes with exactly these counts.
    bool fixed_counts = false;
    std::uint32_t triangle_count = 0;
    std::uint32_t sphere_count = 0;
    // With fixed counts, the lights' and the largest planar mirror's triangle
    // counts too (-D WP_LIGHT_COUNT=n -D WP_MIRROR_GROUP_TRIANGLES=m), so the
    // light pick and the mirror outline test are fixed-count loops, not
    // data-dependent ones that would stop shade's vectorisation
    // (kernels/lights.h, kernels/mirror_light.h, docs/profiling.md).
    std::uint32_t light_count = 0;
    std::uint32_t mirror_group_triangles = 0;
    // With fixed counts, shadow rays test only the triangles that can block
    // them: not the scene's bounding faces (render/shadow_occluders.hpp),
    // -D WP_SHADOW_OCCLUDER_COUNT=n -D WP_SHADOW_OCCLUDERS=i,j,... Off when
    // every triangle can (nothing to gain) or IntegratorOptions says so.
    bool shadow_culling = false;
    std::vector<std::uint32_t> shadow_occluders; // triangle numbers, ascending
    // Large scenes: traversal through a bounding volume hierarchy
    // (-D WP_USE_BVH=1, kernels/bvh.h). Like fixed counts an acceleration,
    // not a feature: the images are the same either way, up to which of two
    // primitives at exactly the same distance is reported.
    bool bvh = false;

    // Every feature and runtime counts, no hierarchy: valid for any scene.
    static SceneFeatures all() {
        return {};
    }
    // The general kernels for a scene: every feature, runtime counts, and the
    // scene's hierarchy if it has one (a large scene stays fast).
    static SceneFeatures general_for(const SceneFeatures& scene) {
        SceneFeatures f = all();
        f.bvh = scene.bvh;
        return f;
    }
    // The -D options that compile exactly these features, e.g.
    // "-D WP_HAS_TRIANGLES=1 -D WP_HAS_SPHERES=0 ... -D WP_TRIANGLE_COUNT=26 -D WP_SPHERE_COUNT=0".
    std::string build_options() const;
    // "triangles spheres diffuse mirror lights", then "; counts 26+2" with
    // fixed counts (and "; shadow tests 5 of 26 triangles" with shadow
    // culling) or "; bvh" with a hierarchy.
    std::string describe() const;
};

// The features of a scene; fixed counts when it has at most
// `max_fixed_count_primitives` primitives (0 turns them off).
SceneFeatures analyse_features(const Scene& scene,
                               std::uint32_t max_fixed_count_primitives = kMaxFixedCountPrimitives);

// The scene buffers' contents: one member per row of WP_SCENE_BUFFERS
// (kernels/wp_shared.h), of the same name.
struct DeviceScene {
    std::vector<WpTriangle> triangles;
    std::vector<WpSphere> spheres;
    std::vector<WpMaterial> materials;
    std::vector<WpLight> lights;                    // emissive triangles with their area CDF
    std::vector<WpShadingNormals> triangle_normals; // of the triangles that have them
    std::vector<WpBvhNode> bvh_nodes;               // empty without a hierarchy
    std::vector<WpMirrorGroup> mirror_groups;       // planar mirrors (render/planar_mirrors.hpp)
    std::vector<WpTriangle> mirror_triangles;       // copies of their triangles
    std::vector<wp_uint> mirror_spheres;            // with lights: the spheres of a mirror material
    std::vector<WpTriangleUvs> triangle_uvs; // of the triangles that have them (with textures)
    std::vector<WpTexture> textures;
    std::vector<wp_uint> texels;             // the bitmaps' (WpTexture.first)
    std::vector<WpEmitter> emitters;         // point, spot, directional, constant, envmap; the
                                             // environment (constant or envmap) first
    std::vector<wp_float> environment_cdf;   // an envmap's sampling tables (lights/envmap.h)
    std::vector<WpInstance> instances;       // in the top-level hierarchy's leaf order
    std::vector<WpTriangle> group_triangles; // every shape group's once, in object space
    std::vector<WpBvhNode> group_bvh_nodes;  // a hierarchy per group (WpInstance.root)
    // Host only: each instance's box in the device's world frame, widened
    // for the rounding of its ray's map into object space (device_scene.cpp).
    std::vector<Bounds3f> instance_boxes;
    std::uint64_t instanced_triangles = 0; // host only: the triangles the instances place
    BvhStats bvh_stats;
    float light_area = 0.0f; // total emissive area
    // The probability that next-event estimation chooses an emitter rather
    // than the emissive triangles (by emitted power; 0 without emitters).
    float emitter_pick = 0.0f;
    WpCamera camera{};
    int width = 0;
    int height = 0;
};

// A double-precision point or vector as the kernels' float4 (w as given).
wp_float4 to_float4(const glm::dvec3& v, double w = 0.0);

// Throws std::runtime_error unless `materials` materials and `normal_sets`
// triangles with vertex normals fit the indices a WpTriangle holds as float
// values (at most WP_TRIANGLE_INDEX_LIMIT each, wp_shared.h).
void check_triangle_indices(std::size_t materials, std::size_t normal_sets);

// Fills each light's guide (WpLight.guide, kernels/wp_shared.h): entry k the
// first light whose cdf exceeds k / count. Part of flatten_scene.
void set_light_guides(std::vector<WpLight>& lights);

// Converts to float32 and builds the light table (by `pick`: render/light_pick.hpp),
// and with `hierarchy` the bounding volume hierarchy over triangles, spheres and
// instances (a scene with instances needs it: std::logic_error without); the
// camera basis is scaled so that film coordinates in [-1, 1] span the field of
// view. Each shape group gets its own hierarchy, built once however many
// instances place it.
DeviceScene flatten_scene(const Scene& scene, bool hierarchy = false,
                          LightPick pick = LightPick::Power);

// flatten_scene in two steps, so that a caller may free the scene's
// triangles between them (render/prepared_scene.hpp): everything but the
// hierarchy (with `hierarchy` false, the whole of flatten_scene), then, with
// `hierarchy`, add_hierarchy, which needs only the flattened arrays and the
// scene's materials.
DeviceScene flatten_without_hierarchy(const Scene& scene, bool hierarchy, LightPick pick);
void add_hierarchy(DeviceScene& scene, const std::vector<Material>& materials);

// How many hierarchies add_hierarchy has built in this process: a render on
// several devices builds one (tests/render/test_multi_device.cpp).
std::uint64_t scene_hierarchies_built();

// The scene's textures as WpTexture rows into out.textures, their bitmaps'
// texels one after another in out.texels (each file once); part of
// flatten_scene.
void flatten_textures(const Scene& scene, DeviceScene& out);

// The box the hierarchy gives each primitive (the triangles' first, then the
// spheres', then the instances'): the primitive's float32 bounds, widened so
// that every hit the device's intersection tests report lies inside (see
// device_scene.cpp).
std::vector<Bounds3f> primitive_boxes(const DeviceScene& scene);

} // namespace wp
