/* Data shared by the host (C++) and the kernels (OpenCL C 1.2).
 *
 * Both sides include this one header, so a struct cannot drift between them;
 * tests/kernels/test_layout.cpp still checks every size and offset on the device
 * against the host's, because the two compilers lay structs out separately.
 * Rules that keep the layouts equal: 16-byte vectors first, then 4-byte
 * scalars, explicit padding to a multiple of 16 bytes, no bool, no pointers.
 */
#ifndef WP_SHARED_H
#define WP_SHARED_H

#ifdef __OPENCL_VERSION__
/* No a*b+c contraction into FMA anywhere: the watertight triangle test relies
 * on exactly antisymmetric edge functions, and host references expect the
 * same rounding on every device. This header comes first in every stage. */
#pragma OPENCL FP_CONTRACT OFF
typedef uint wp_uint;
typedef float wp_float;
typedef float4 wp_float4;
#else
#include <CL/cl_platform.h>
#include <string.h>
typedef cl_uint wp_uint;
typedef cl_float wp_float;
typedef cl_float4 wp_float4;
#endif

/* For functions that must be inlined into their callers. */
#if defined(__clang__) || defined(__GNUC__)
#define WP_ALWAYS_INLINE __attribute__((always_inline))
#else
#define WP_ALWAYS_INLINE
#endif

/* The material kinds, one row each: X(KIND, Name, name, value, bsdf, glossy).
 * Everything that knows about kinds is generated from or checked against
 * this table (docs/architecture.md, "Adding a material"):
 *   WP_MATERIAL_KIND   the constant in WpMaterial.kind (below);
 *   Name               MaterialKind::Name on the host (src/scene/scene.hpp);
 *   name               the scene file's "type" (src/scene/load.cpp) and the
 *                      feature's name (SceneFeatures::name, "wavepath info");
 *   bsdf               1 for a kind that scatters: its header
 *                      kernels/bsdf/name.h, its dispatch line (kernels/bsdf.h)
 *                      and its feature switch WP_HAS_KIND (kernels/
 *                      scene_features.h), which compiles the code in only for
 *                      scenes that use it; 0 for a kind with no BSDF at all;
 *   glossy             1 for a kind whose BSDF is neither Lambertian nor delta:
 *                      next-event estimation there is weighed against BSDF
 *                      sampling even where Lambertian vertices are not
 *                      (kernels/bsdf.h, WP_HAS_GLOSSY and WP_MIS_EVERY_VERTEX).
 * Values are the order of the rows: they are stored in checkpoints' scene
 * hashes, so a new kind goes at the end. WP_MATERIALS_WITH(X, a) hands every
 * row to X with `a` first, for tables generated from this one (the host's
 * feature rows, src/render/device_scene.hpp). */
#define WP_MATERIALS_WITH(X, a)                                                                    \
    X(a, DIFFUSE, Diffuse, diffuse, 0u, 1, 0)       /* Lambertian */                               \
    X(a, MIRROR, Mirror, mirror, 1u, 1, 0)          /* perfect specular reflection */              \
    X(a, EMITTER, Emitter, emitter, 2u, 0, 0)       /* emits, reflects nothing */                  \
    X(a, CONDUCTOR, Conductor, conductor, 3u, 1, 0) /* smooth metal, Fresnel */                    \
    X(a, ROUGHCONDUCTOR, RoughConductor, roughconductor, 4u, 1, 1) /* microfacet metal */          \
    X(a, DIELECTRIC, Dielectric, dielectric, 5u, 1, 0)             /* smooth glass, water */       \
    X(a, THINDIELECTRIC, ThinDielectric, thindielectric, 6u, 1, 0) /* a pane of no thickness */    \
    X(a, PLASTIC, Plastic, plastic, 7u, 1, 0)                      /* diffuse under a coating */   \
    X(a, ROUGHDIELECTRIC, RoughDielectric, roughdielectric, 8u, 1, 1) /* frosted glass */          \
    X(a, ROUGHPLASTIC, RoughPlastic, roughplastic, 9u, 1, 1) /* diffuse under a rough coating */
#define WP_MATERIALS(X) WP_MATERIALS_WITH(WP_MATERIAL_ROW_OF, X)
#define WP_MATERIAL_ROW_OF(X, ...) X(__VA_ARGS__)

/* WP_IF(flag)(text): text when flag is 1, nothing when 0 (for the table's bsdf
 * column). */
#define WP_IF(flag) WP_IF_##flag
#define WP_IF_0(...)
#define WP_IF_1(...) __VA_ARGS__

/* Material kinds (WpMaterial.kind): WP_MATERIAL_DIFFUSE, ... */
#define WP_MATERIAL_ENUMERATOR(KIND, Name, name, value, bsdf, glossy) WP_MATERIAL_##KIND = value,
enum { WP_MATERIALS(WP_MATERIAL_ENUMERATOR) WP_MATERIAL_KIND_COUNT };
#undef WP_MATERIAL_ENUMERATOR

/* What a sampled direction is (WpBsdfSample.flags, kernels/bsdf/interface.h):
 * one side, times one kind of lobe. */
#define WP_BSDF_REFLECTION 1u
#define WP_BSDF_TRANSMISSION 2u
#define WP_BSDF_DIFFUSE 4u
#define WP_BSDF_GLOSSY 8u
#define WP_BSDF_DELTA 16u /* next-event estimation cannot reach it */

/* Entries of a roughplastic's transmittance table (Mitsuba's
 * MI_ROUGH_TRANSMITTANCE_RES). */
#define WP_ROUGH_TRANSMITTANCE_RES 64

/* Microfacet distributions (WpMaterial.distribution), Mitsuba's names. */
#define WP_MICROFACET_BECKMANN 0u
#define WP_MICROFACET_GGX 1u

/* Marks a ray that hit nothing (WpHit.primitive). */
#define WP_NO_HIT 0xffffffffu

/* Path flags (path_flags[]). */
#define WP_PATH_SPECULAR 1u /* the last bounce was delta (or none yet): emitters count */
/* Bits 1-3 hold the path's history class (WP_PATH_TYPE_*, kernels/path_type.h),
 * kept only when the kernels are built with WP_PATH_TYPES. */
#define WP_PATH_HISTORY_SHIFT 1u
#define WP_PATH_HISTORY_BITS (7u << WP_PATH_HISTORY_SHIFT)
/* The path went diffuse vertex -> one planar mirror -> here: emission found
 * now gets the multiple importance sampling weight against mirrored-light
 * sampling (kernels/mirror_light.h). Set only with WP_MIRROR_NEE. */
#define WP_PATH_PLANAR_MIRROR 16u
/* The same after a mirror sphere, whose number (into spheres[]) the bits from
 * WP_PATH_SPHERE_SHIFT on hold. Set only with WP_MIRROR_NEE and
 * WP_HAS_MIRROR_SPHERES. */
#define WP_PATH_SPHERE_MIRROR 32u
/* The last bounce was at a vertex whose light sample is weighed by multiple
 * importance sampling (wp_bsdf_weighs_light, kernels/bsdf.h: every non-delta
 * one with the default --mis power, else the glossy kinds): emission found
 * now takes the weight against that next-event estimation, with the BSDF
 * density of the bounce in mirror_vertex.w. */
#define WP_PATH_GLOSSY 64u
#define WP_PATH_SPHERE_SHIFT 8u
#define WP_PATH_SPHERE_BITS 0xffffff00u

/* Path types: every contribution to a pixel falls in exactly one, by the
 * bounces before the light reached the path (docs/convergence.md, "Where the
 * error is"). WpFrame.path_types, a sum of (1u << type), selects the ones a
 * render adds, in kernels built with WP_PATH_TYPES; the host builds them so
 * only for `--path-types`. */
#define WP_PATH_TYPE_CAMERA 0u   /* an emitter seen from the camera */
#define WP_PATH_TYPE_DIRECT 1u   /* light at the first vertex, a diffuse one */
#define WP_PATH_TYPE_INDIRECT 2u /* after two or more diffuse bounces, no mirror */
#define WP_PATH_TYPE_MIRROR 3u   /* the first vertex is a mirror */
#define WP_PATH_TYPE_CAUSTIC 4u  /* a diffuse first vertex, a mirror after it */
#define WP_PATH_TYPE_COUNT 5u

/* Counters the kernels bump with atomics (one buffer of WP_COUNTER_COUNT
 * uints). The two ray queues swap roles every iteration, so each keeps its
 * length in its own entry and kernels are told which entry is theirs. */
#define WP_COUNTER_QUEUE_A 0u     /* length of ray queue A */
#define WP_COUNTER_QUEUE_B 1u     /* length of ray queue B */
#define WP_COUNTER_SHADOW_RAYS 2u /* length of the shadow-ray queue */
#define WP_COUNTER_FINISHED 3u    /* length of the finished-path queue */
#define WP_COUNTER_CAPPED 4u      /* paths cut by the safety depth cap */
#define WP_COUNTER_NONFINITE 5u   /* samples dropped at the film for NaN or Inf */
#define WP_COUNTER_MIRROR_SHADOW_RAYS                                                              \
    6u /* the mirror queue: two-leg shadow rays (mirror_light.h) */
#define WP_COUNTER_COUNT 8u

/* The most bounces the tail kernel (tail.cl) traces a path in one launch. */
#define WP_TAIL_BOUNCES 32u

/* The keys shade's queue is sorted by (kernels/shade_sort.cl, with
 * --shade-order sorted): the material kind a ray hit, or
 * WP_SHADE_KEY_MISS for a ray that left the scene. */
#define WP_SHADE_KEY_MISS ((wp_uint)WP_MATERIAL_KIND_COUNT)
#define WP_SHADE_KEY_COUNT (WP_MATERIAL_KIND_COUNT + 1)

/* The largest work-group the host launches (src/render/wavefront.cpp): shade
 * compacts its queue pushes through local arrays of this many entries. */
#define WP_MAX_WORK_GROUP_SIZE 256u

/* A triangle, 48 bytes: vertices in xyz. Its front face is the side of
 * cross(v1 - v0, v2 - v0); only emitters care which side is the front. The
 * w lanes, which no geometric code reads, hold two uints as float VALUES
 * (read and written only through the accessors below; exact up to
 * WP_TRIANGLE_INDEX_LIMIT = 2^24, which the host checks): v0.w its material,
 * v1.w `normals`, 0 or k + 1 for shading normals in triangle_normals[k]; v2.w
 * `uvs`, 0 or k + 1 for texture coordinates in triangle_uvs[k] (set only in
 * scenes with textures). A 0.0f lane is 0, so material 0 without normals or
 * texture coordinates is the default.
 *
 * Not the uints' bits: small uints read as floats are denormals, and the
 * vector code that loads a vertex as a float4 carries its w lane through
 * the arithmetic on xyz, where every denormal operand costs the CPU extra
 * cycles. Storing the bits cost shade a third of its time on PoCL (measured,
 * docs/performance.md, "Shade, measured"). */
#define WP_TRIANGLE_INDEX_LIMIT 16777216u
typedef struct {
    wp_float4 v0;
    wp_float4 v1;
    wp_float4 v2;
} WpTriangle;

#ifdef __OPENCL_VERSION__
static inline wp_uint wp_triangle_material(const WpTriangle* t) {
    return (wp_uint)t->v0.w;
}
static inline wp_uint wp_triangle_normals(const WpTriangle* t) {
    return (wp_uint)t->v1.w;
}
static inline wp_uint wp_triangle_uvs(const WpTriangle* t) {
    return (wp_uint)t->v2.w;
}
#else
static inline wp_uint wp_triangle_material(const WpTriangle* t) {
    return (wp_uint)t->v0.s[3];
}
static inline wp_uint wp_triangle_normals(const WpTriangle* t) {
    return (wp_uint)t->v1.s[3];
}
/* Both setters take values up to WP_TRIANGLE_INDEX_LIMIT (the caller checks). */
static inline void wp_set_triangle_material(WpTriangle* t, wp_uint material) {
    t->v0.s[3] = (wp_float)material;
}
static inline void wp_set_triangle_normals(WpTriangle* t, wp_uint normals) {
    t->v1.s[3] = (wp_float)normals;
}
static inline void wp_set_triangle_uvs(WpTriangle* t, wp_uint uvs) {
    t->v2.s[3] = (wp_float)uvs;
}
#endif

/* A triangle's vertex normals for shading (unit, xyz), in vertex order. */
typedef struct {
    wp_float4 n0;
    wp_float4 n1;
    wp_float4 n2;
} WpShadingNormals;

/* A triangle's texture coordinates, in vertex order: vertex i has (u.si, v.si)
 * (the w lanes are unused). */
typedef struct {
    wp_float4 u;
    wp_float4 v;
} WpTriangleUvs;

typedef struct {
    wp_float4 center_radius; /* xyz centre, w radius */
    wp_uint material;
    wp_uint pad0, pad1, pad2;
} WpSphere;

/* A material: the parameters of every kind side by side; each BSDF reads its
 * own (kernels/bsdf/KIND.h). */
typedef struct {
    /* rgb in [0, 1]; conductors and dielectrics: specular_reflectance;
     * plastic: diffuse_reflectance */
    wp_float4 reflectance;
    wp_float4 emission; /* rgb radiance from the front face */
    /* conductors: the real part of the complex IOR, rgb; dielectrics and
     * plastic: int_ior / ext_ior in every channel */
    wp_float4 eta;
    wp_float4 k;              /* conductors: imaginary part (absorption), rgb */
    wp_float4 transmittance;  /* dielectrics: specular_transmittance, rgb in [0, 1] */
    wp_float4 specular;       /* plastic: the coating's specular_reflectance, rgb in [0, 1] */
    wp_uint kind;             /* WP_MATERIAL_* */
    wp_uint distribution;     /* rough kinds: WP_MICROFACET_* */
    wp_uint fresnel;          /* conductors: 1, the Fresnel term of eta and k; 0, F = 1 ("none") */
    wp_float alpha_u;         /* rough kinds: roughness along the tangent, > 0 */
    wp_float alpha_v;         /* ... and along the bitangent */
    wp_float fdr_int;         /* plastics: the coating's diffuse Fresnel reflectance from inside */
    wp_float specular_weight; /* plastics: the share of samples steered to the coating */
    wp_uint nonlinear;        /* plastics: Mitsuba's `nonlinear` */
    /* Textured parameters (kernels/textures/texture.h): 0, the constant
     * above; k + 1, the value of textures[k] at the hit point, which replaces
     * it before the BSDF sees the material. Roughness takes the texture's
     * luminance, as Mitsuba's float textures do. */
    wp_uint reflectance_texture;
    wp_uint specular_texture;
    wp_uint transmittance_texture;
    wp_uint alpha_u_texture;
    wp_uint alpha_v_texture;
    wp_uint pad0, pad1, pad2;
    /* roughplastic: the rough coating's transmittance from outside at incidence
     * cosines i / (WP_ROUGH_TRANSMITTANCE_RES - 1), interpolated linearly as
     * Mitsuba does (computed by the host, src/scene/material.cpp). Carried by
     * every material rather than in a buffer of its own, because a BSDF sees
     * its WpMaterial alone (kernels/bsdf/interface.h); a kernel that never
     * reads it (roughplastic compiled out) never loads it. */
    wp_float rough_transmittance[WP_ROUGH_TRANSMITTANCE_RES];
} WpMaterial;

/* The texture kinds, one row each: X(KIND, Name, name, value), Mitsuba 3's
 * names. Each has its header kernels/textures/NAME.h and its feature switch
 * WP_HAS_KIND_TEXTURE (kernels/scene_features.h), on only for scenes that use
 * it; WP_TEXTURES_WITH(X, a) hands every row to X with `a` first. */
#define WP_TEXTURES_WITH(X, a)                                                                     \
    X(a, BITMAP, Bitmap, bitmap, 0u)                   /* an image file, filtered */               \
    X(a, CHECKERBOARD, Checkerboard, checkerboard, 1u) /* two colours in squares of 1/2 */
#define WP_TEXTURES(X) WP_TEXTURES_WITH(WP_MATERIAL_ROW_OF, X)

#define WP_TEXTURE_ENUMERATOR(KIND, Name, name, value) WP_TEXTURE_##KIND = value,
enum { WP_TEXTURES(WP_TEXTURE_ENUMERATOR) WP_TEXTURE_KIND_COUNT };
#undef WP_TEXTURE_ENUMERATOR

/* How a bitmap's texels are stored in texels[] (WpTexture.format). */
#define WP_TEXELS_RGBA8 0u      /* one uint per texel: r in the low byte, then g, b (linear) */
#define WP_TEXELS_RGBA8_SRGB 1u /* the same, sRGB-encoded: decoded to linear per texel */
#define WP_TEXELS_RGB32F 2u     /* three uints per texel: the bits of r, g, b as floats */

/* What a bitmap does outside [0, 1)^2 (WpTexture.wrap), Mitsuba's wrap_mode. */
#define WP_TEXTURE_WRAP_REPEAT 0u
#define WP_TEXTURE_WRAP_MIRROR 1u
#define WP_TEXTURE_WRAP_CLAMP 2u

/* How a bitmap is filtered (WpTexture.filter), Mitsuba's filter_type. */
#define WP_TEXTURE_FILTER_BILINEAR 0u
#define WP_TEXTURE_FILTER_NEAREST 1u

/* A texture, 96 bytes. Every kind maps the hit point's (u, v) through its
 * affine transform first (Mitsuba's to_uv): u' = dot(to_u.xyz, (u, v, 1)),
 * v' = dot(to_v.xyz, (u, v, 1)). A bitmap's row 0 is the top of the image
 * file and lies at v' = 0, as in Mitsuba (the OBJ reader flips the file's v,
 * as Mitsuba's does). */
typedef struct {
    wp_float4 color0; /* checkerboard: the squares where u' and v' agree (rgb) */
    wp_float4 color1; /* ... and the others */
    wp_float4 to_u;
    wp_float4 to_v;
    wp_uint kind;   /* WP_TEXTURE_* */
    wp_uint format; /* bitmap: WP_TEXELS_* */
    wp_uint width;  /* bitmap: texels */
    wp_uint height;
    wp_uint first;  /* bitmap: where its texels start in texels[] (in uints) */
    wp_uint wrap;   /* bitmap: WP_TEXTURE_WRAP_* */
    wp_uint filter; /* bitmap: WP_TEXTURE_FILTER_* */
    wp_uint pad0;
} WpTexture;

/* One emissive triangle, chosen with probability proportional to its area:
 * cdf is the running sum of areas up to and including this one, divided by
 * the total, so light sampling is a search for the first cdf > u. `guide`
 * makes that search O(1) for many lights (the cutpoint method, Chen and
 * Asau 1974): in entry k, the first light whose cdf exceeds k / count, where
 * the search for any u in [k / count, (k + 1) / count) may start
 * (kernels/lights.h; src/render/device_scene.cpp fills it). */
typedef struct {
    wp_uint triangle;
    wp_float cdf;
    wp_uint guide;
    wp_uint pad0;
} WpLight;

/* The emitters that are not emitting surfaces (Mitsuba 3's plugins of the
 * same names, docs/lights-and-camera.md): WpEmitter.kind. */
#define WP_EMITTER_POINT 0u       /* intensity from a point, in every direction */
#define WP_EMITTER_SPOT 1u        /* a point's intensity within a cone, linear falloff */
#define WP_EMITTER_DIRECTIONAL 2u /* irradiance from one direction: a sun */
#define WP_EMITTER_CONSTANT 3u    /* uniform radiance from every direction: a sky */
#define WP_EMITTER_ENVMAP 4u      /* radiance from every direction, by an image: an HDR sky */
#define WP_EMITTER_SPHERE 5u      /* an emitting sphere: a sphere whose material emits */

/* One such emitter, 160 bytes. Lights are chosen by emitted power
 * (src/render/device_scene.cpp): the emissive triangles together with
 * probability 1 - WpFrame.emitter_pick (then one by area, WpLight), each
 * emitter here with probability `pick`; `cdf` is the running sum of the
 * area lights' and the emitters' probabilities up to and including this one
 * (the last 1). The environment (a constant or an envmap emitter, at most
 * one), if any, is emitters[0], so that a ray that escapes finds it without a
 * search. An envmap's image and its sampling tables are described in
 * kernels/lights/envmap.h. */
typedef struct {
    wp_float4 position;  /* point, spot: xyz (in the device's float frame) */
    wp_float4 direction; /* spot: unit axis it shines along; directional: unit direction the
                            light travels */
    wp_float4 radiance;  /* rgb: point, spot: intensity (scaled to the float frame's lengths);
                            directional: irradiance; constant: radiance */
    wp_uint kind;        /* WP_EMITTER_* */
    wp_float pick;       /* the probability next-event estimation chooses it */
    wp_float cdf;
    wp_float reach;      /* directional, constant: a shadow ray's length that leaves the scene */
    wp_float cos_cutoff; /* spot: cos(cutoff_angle) */
    wp_float cos_beam;   /* spot: cos(beam_width) */
    wp_float cutoff;     /* spot: cutoff_angle, radians */
    wp_float inv_transition; /* spot: 1 / (cutoff_angle - beam_width), radians */
    wp_float4 to_local[3];   /* envmap: the rows of its world-to-map rotation */
    wp_uint texels_first;    /* envmap: its image in texels[] (WP_TEXELS_RGB32F) */
    wp_uint width;           /* envmap: the image's size in texels */
    wp_uint height;
    wp_uint cdf_first; /* envmap: its sampling tables in environment_cdf[] (lights/envmap.h) */
    wp_uint sphere;    /* sphere: its number in spheres[] (position: centre xyz, radius w) */
    wp_uint pad0, pad1, pad2;
} WpEmitter;

/* A planar mirror: coplanar mirror triangles (without vertex normals) found
 * by the host (src/render/planar_mirrors.hpp), for next-event estimation
 * through it (kernels/mirror_light.h). plane: unit normal xyz, offset w
 * (points p of the plane have dot(normal, p) == w); its triangles are
 * mirror_triangles[first .. first + count - 1], copies of the scene's. */
typedef struct {
    wp_float4 plane;
    wp_uint first;
    wp_uint count;
    wp_uint pad0, pad1;
} WpMirrorGroup;

/* A node of the bounding volume hierarchy, eight children wide: the
 * builder's binary tree (src/scene/bvh.hpp) collapsed by surface area
 * (src/render/wide_bvh.cpp), 256 bytes of scalars. Child i's box is
 * lower_x[i] .. upper_x[i] and so on (an array per coordinate, so the eight box
 * tests are one float8 test), and count[i] says what it is: 0, the
 * node bvh_nodes[child[i]]; n > 0, a leaf of the primitives child[i] ..
 * child[i] + n - 1 (all triangles or all spheres: primitives are stored in
 * leaf order); WP_BVH_EMPTY, no child. nodes[0] is the root. Every box holds
 * the primitives below it with room for the intersection tests' rounding. */
#define WP_BVH_WIDTH 8
typedef struct {
    wp_float lower_x[WP_BVH_WIDTH], upper_x[WP_BVH_WIDTH];
    wp_float lower_y[WP_BVH_WIDTH], upper_y[WP_BVH_WIDTH];
    wp_float lower_z[WP_BVH_WIDTH], upper_z[WP_BVH_WIDTH];
    wp_uint child[WP_BVH_WIDTH];
    wp_uint count[WP_BVH_WIDTH];
} WpBvhNode;

#define WP_BVH_EMPTY 0xffffffffu

/* An instance of a shape group (Mitsuba's shapegroup and instance,
 * kernels/instance.h): the group's triangles, stored once in object space in
 * group_triangles[] under their own hierarchy in group_bvh_nodes[] (nodes
 * as above, leaves naming group_triangles), placed in the scene by an affine
 * map. to_world's rows take an object point p to the device's world frame,
 * world_i = dot(to_world[i].xyz, p) + to_world[i].w; to_object's rows are
 * the inverse. The top-level hierarchy (bvh_nodes) holds instances as
 * primitives after the triangles and spheres; a hit on triangle k of the
 * group's, k counted from first_triangle, is primitive number
 * triangle_count + sphere_count + first_primitive + (k - first_triangle)
 * (primitive.h decodes it). mirrored: the map's determinant is negative, so
 * the world winding normal is the object normal's reverse (the front face
 * follows the object normal, as in Mitsuba). */
typedef struct {
    wp_float4 to_world[3];
    wp_float4 to_object[3];
    wp_uint root;            /* its group's root node in group_bvh_nodes[] */
    wp_uint first_triangle;  /* its group's first triangle in group_triangles[] */
    wp_uint first_primitive; /* its hits' numbers past the plain primitives (above) */
    wp_uint mirrored;
} WpInstance;

/* The traversal stack's entries (kernels/bvh.h). An eight-wide node leaves
 * up to seven children on the stack when the walk goes down to its eighth;
 * the host's collapse keeps nodes narrower where a path would need more than
 * this (src/render/wide_bvh.cpp), which the binary tree's depth cap below
 * always allows. 64 entries: the private memory GPUs give each work-item is
 * small, and 64 measured as fast as 128 on PoCL (docs/performance.md,
 * "Eight-wide nodes"). */
#define WP_BVH_STACK_SIZE 64

/* The deepest leaf of the binary tree the host builds. */
#define WP_BVH_MAX_DEPTH 41u

/* The pixel reconstruction filters, one row each: X(KIND, Name, name, value,
 * sampled), Mitsuba 3's names. A sample's position in its pixel is drawn
 * from the filter (filter importance sampling, kernels/camera.h), so that the
 * film stays a per-pixel sum of equally weighted samples (no splatting) and
 * the image does not depend on how the samples are split:
 *   WP_FILTER_KIND  the constant in WpCamera.filter;
 *   Name            FilterKind::Name on the host (src/scene/scene.hpp);
 *   name            the scene file's filter "type" (src/scene/load.cpp) and,
 *                   with `_filter`, the feature's name;
 *   sampled         1 for a filter with its own sampling code, compiled in
 *                   only for scenes that use it (the feature switch
 *                   WP_HAS_KIND_FILTER, kernels/scene_features.h); 0 for the
 *                   box, a uniform point in the pixel, which is always there.
 * WP_FILTERS_WITH(X, a) hands every row to X with `a` first. */
#define WP_FILTERS_WITH(X, a)                                                                      \
    X(a, BOX, Box, box, 0u, 0)                /* one pixel wide, uniform: radius 1/2 */            \
    X(a, TENT, Tent, tent, 1u, 1)             /* 1 - |x| / radius, radius 1 by default */          \
    X(a, GAUSSIAN, Gaussian, gaussian, 2u, 1) /* exp(-x^2 / (2 stddev^2)) - its value at 4 stddev  \
                                               */
#define WP_FILTERS(X) WP_FILTERS_WITH(WP_MATERIAL_ROW_OF, X)

#define WP_FILTER_ENUMERATOR(KIND, Name, name, value, sampled) WP_FILTER_##KIND = value,
enum { WP_FILTERS(WP_FILTER_ENUMERATOR) WP_FILTER_KIND_COUNT };
#undef WP_FILTER_ENUMERATOR

/* The camera: a pinhole ray through film position (sx, sy) in [-1, 1]^2
 * (x right, y up) has direction forward + sx * right + sy * up, where right
 * and up are already scaled by the half-extent of the image plane at unit
 * distance. With a thin lens (Mitsuba's `thinlens`) the ray leaves a point of
 * the aperture disk instead of the eye and passes through the point where the
 * pinhole ray meets the plane of focus (kernels/camera.h). */
typedef struct {
    wp_float4 eye;
    wp_float4 forward;
    wp_float4 right;
    wp_float4 up;
    wp_float4 lens_right;   /* thin lens: the unit right vector times the aperture radius
                               (xyz), the focus distance along forward (w) */
    wp_float4 lens_up;      /* the unit up vector times the aperture radius (xyz), the
                               aperture radius (w): 0 is a pinhole */
    wp_uint filter;         /* WP_FILTER_* */
    wp_float filter_radius; /* pixels: where the filter ends (tent, gaussian) */
    wp_float filter_scale;  /* gaussian: 1 / (stddev sqrt(2)) */
    wp_float filter_bias;   /* gaussian: exp(-(radius filter_scale)^2), its value at the radius */
} WpCamera;

/* Everything the kernels need besides buffers, passed by value.
 *
 * A render call computes samples [first_sample, first_sample + sample_count)
 * of every pixel with a pool of pool_size path slots. Slot i owns pixels i,
 * i + pool_size, i + 2 pool_size, ... and works through its own list of
 * (pixel, sample) tasks; no two slots ever write the same pixel, so the film
 * needs no atomics and the image does not depend on scheduling. */
typedef struct {
    WpCamera camera;
    wp_uint width; /* pixels */
    wp_uint height;
    wp_uint seed; /* user seed: the image is a function of it */
    wp_uint first_sample;
    wp_uint sample_count;
    wp_uint pool_size; /* path slots, at most width * height */
    wp_uint triangle_count;
    wp_uint sphere_count;
    wp_uint light_count;
    wp_float light_area;         /* total emissive area: 1 / pdf of uniform area sampling */
    wp_uint max_depth;           /* safety cap on bounces; paths cut are counted */
    wp_uint mirror_group_count;  /* planar mirrors (WpMirrorGroup) */
    wp_uint mirror_sphere_count; /* mirror spheres (mirror_spheres) */
    wp_uint path_types;          /* the path types a render adds, with WP_PATH_TYPES */
    wp_uint emitter_count;       /* WpEmitter entries */
    wp_float emitter_pick;       /* the probability of choosing an emitter rather than the
                                    emissive triangles: 0 without emitters, so that a frame
                                    left zero samples the triangles alone */
    wp_uint instance_count;      /* WpInstance entries (kernels/instance.h) */
} WpFrame;

/* What changes from one launch of a stage to the next, passed by value after
 * the frame. Every stage takes the same arguments (kernels/stage.h), so a
 * stage reads only the fields that concern it:
 *   generate    count slots: work-item i takes slot i, or, with
 *               from_finished, the slot finished_queue[i]; it pushes the new
 *               camera rays onto ray queue `ray_queue`.
 *   intersect,  read ray queue `ray_queue` (its length is in
 *   shade       counters[ray_queue], as generate appended to it after the host
 *               last looked); shade pushes survivors onto the other queue.
 *               With `sorted`, shade takes its slots from shade_order, the
 *               same queue sorted by material kind (shade_sort.cl).
 *   shadow      count shadow rays (mirror_shadow: count two-leg rays of the
 *               mirror queue, shadow_queue + pool_size).
 *   accumulate  count finished paths. */
typedef struct {
    wp_uint count;
    wp_uint ray_queue; /* 0 or 1: WP_COUNTER_QUEUE_A or WP_COUNTER_QUEUE_B */
    wp_uint from_finished;
    wp_uint sorted; /* shade: take the slots from shade_order, not the ray queue */
} WpLaunch;

/* Every device buffer, declared once. The stage kernels' parameter lists
 * (kernels/stage.h) and the host's buffers and argument binding
 * (src/render/device_buffers.hpp) are both generated from these lists, so a
 * new buffer is one line here (and, for a scene buffer, the DeviceScene
 * member of the same name that fills it) and cannot shift another argument.
 *
 * WP_SCENE_BUFFERS: X(name, element type), read-only, uploaded from the
 * DeviceScene member `name`.
 *
 * WP_PATH_BUFFERS: X(name, element type, per slot, per pixel, fixed): work
 * buffers of per_slot x pool_size + per_pixel x width x height + fixed
 * elements. */
#define WP_SCENE_BUFFERS(X)                                                                        \
    X(triangles, WpTriangle)                                                                       \
    X(spheres, WpSphere)                                                                           \
    X(materials, WpMaterial)                                                                       \
    X(lights, WpLight)                                                                             \
    X(triangle_normals, WpShadingNormals) /* shading normals of the triangles that have them */    \
    X(bvh_nodes, WpBvhNode)               /* with WP_USE_BVH; a dummy without */                   \
    X(mirror_groups, WpMirrorGroup)       /* planar mirrors (kernels/mirror_light.h) */            \
    X(mirror_triangles, WpTriangle)       /* their triangles */                                    \
    X(mirror_spheres, wp_uint)            /* the mirror spheres' numbers in spheres[] */           \
    X(triangle_uvs, WpTriangleUvs) /* texture coordinates of the triangles that have them */       \
    X(textures, WpTexture)         /* with textures; a dummy without */                            \
    X(texels, wp_uint)             /* the bitmaps' texels (WpTexture.format) */                    \
    X(emitters, WpEmitter)         /* point, spot, directional, constant, envmap, sphere */        \
    X(environment_cdf, wp_float)   /* an envmap's sampling tables (kernels/lights/envmap.h) */     \
    X(instances, WpInstance)       /* with WP_HAS_INSTANCES; a dummy without */                    \
    X(group_triangles, WpTriangle) /* the shape groups' triangles, in object space */              \
    X(group_bvh_nodes, WpBvhNode)  /* their hierarchies, one per group */

#define WP_PATH_BUFFERS(X)                                                                         \
    /* path state, one entry per slot (structure of arrays) */                                     \
    X(path_task, wp_uint, 1, 0, 0)  /* tasks done by the slot in this render call */               \
    X(path_pixel, wp_uint, 1, 0, 0) /* the slot's current pixel and sample */                      \
    X(path_sample, wp_uint, 1, 0, 0)                                                               \
    X(path_depth, wp_uint, 1, 0, 0)   /* bounces so far */                                         \
    X(path_flags, wp_uint, 1, 0, 0)   /* WP_PATH_* */                                              \
    X(ray_origin, wp_float4, 1, 0, 0) /* the ray to trace next (xyz) */                            \
    X(ray_direction, wp_float4, 1, 0, 0)                                                           \
    X(throughput, wp_float4, 1, 0, 0)    /* rgb: what the path carries */                          \
    X(radiance, wp_float4, 1, 0, 0)      /* rgb: what it has gathered */                           \
    X(hit_t, wp_float, 1, 0, 0)          /* intersect's closest hit */                             \
    X(hit_primitive, wp_uint, 1, 0, 0)   /* ... and what it hit (WP_NO_HIT) */                     \
    X(shadow_origin, wp_float4, 1, 0, 0) /* the slot's shadow ray (direction w: length) */         \
    X(shadow_direction, wp_float4, 1, 0, 0)                                                        \
    X(shadow_contribution, wp_float4, 1, 0, 0) /* rgb added if unblocked */                        \
    /* next-event estimation through a planar mirror (kernels/mirror_light.h): */                  \
    X(mirror_vertex, wp_float4, 1, 0, 0) /* last non-delta vertex (xyz), its BSDF pdf (w) */       \
    X(mirror_shadow_origin, wp_float4, 1, 0, 0) /* leg 1: to the mirror (w: length) */             \
    X(mirror_shadow_direction, wp_float4, 1, 0, 0)                                                 \
    X(mirror_shadow_origin2, wp_float4, 1, 0, 0) /* leg 2: mirror to light (w: length) */          \
    X(mirror_shadow_direction2, wp_float4, 1, 0, 0)                                                \
    X(mirror_shadow_contribution, wp_float4, 1, 0, 0) /* added if both legs are unblocked */       \
    /* queues of slot indices, pushed with atomics on `counters` */                                \
    X(ray_queues, wp_uint, 2, 0, 0)   /* queues A and B, pool_size entries each */                 \
    X(shadow_queue, wp_uint, 2, 0, 0) /* shadow rays, then (at pool_size) mirror ones */           \
    X(finished_queue, wp_uint, 1, 0, 0)                                                            \
    X(counters, wp_uint, 0, 0, WP_COUNTER_COUNT)                                                   \
    /* the ray queue sorted by what was hit, and its counts per key (kernels/shade_sort.cl) */     \
    X(shade_order, wp_uint, 1, 0, 0)                                                               \
    X(shade_key_counts, wp_uint, 0, 0, 2u * WP_SHADE_KEY_COUNT)                                    \
    /* tail.cl: entry k - 1 counts the paths that traced k rays in one tail launch */              \
    X(tail_lengths, wp_uint, 0, 0, WP_TAIL_BOUNCES)                                                \
    /* the film of the current batch of iterations, per pixel (kernels/accumulate.cl) */           \
    X(film_sum, wp_float4, 0, 1, 0)                                                                \
    X(film_sum_squares, wp_float4, 0, 1, 0)                                                        \
    X(film_odd_sum, wp_float4, 0, 1, 0)                                                            \
    WP_AOV_BUFFERS(X)

/* The AOVs' sums of the current batch, per pixel, added by shade at the camera
 * ray's first hit (kernels/shade.cl, WP_AOV; docs/lights-and-camera.md,
 * "AOVs"). Rows of WP_PATH_BUFFERS like the others; the host allocates them
 * whole only for a render that asks for AOVs, and a one-element dummy
 * otherwise (src/render/device_buffers.cpp). */
#define WP_AOV_BUFFERS(X)                                                                          \
    X(aov_albedo, wp_float4, 0, 1, 0) /* rgb: the material's albedo */                             \
    X(aov_normal, wp_float4, 0, 1, 0) /* xyz: the shading normal facing the camera */              \
    X(aov_depth, wp_float, 0, 1, 0)   /* the distance along the camera ray */

#endif /* WP_SHARED_H */
