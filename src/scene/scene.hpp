// The scene as the user described it: camera, materials and shapes, in double
// precision on the host. The loader (scene/load.hpp) fills it from a JSON file
// and validates every value; render/device_scene.hpp (flatten_scene) turns it into device buffers.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/texture.hpp"
#include "scene/triangle_list.hpp"

#include "wp_shared.h"

namespace wp {

// Thrown for anything wrong with a scene description. The message is one line
// that names the file, the field (as a JSON pointer such as
// "/shapes/3/radius") and, where the parser knows it, the byte position.
class SceneError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The pixel reconstruction filters: the rows of WP_FILTERS (kernels/wp_shared.h),
// with the kernels' values.
#define WP_FILTER_KIND_ENUMERATOR(KIND, Name, name, value, sampled) Name = value,
enum class FilterKind : std::uint32_t { WP_FILTERS(WP_FILTER_KIND_ENUMERATOR) };
#undef WP_FILTER_KIND_ENUMERATOR

struct Camera {
    glm::dvec3 eye{0.0};
    glm::dvec3 look_at{0.0, 0.0, -1.0}; // a point the camera looks at
    glm::dvec3 up{0.0, 1.0, 0.0};
    // Full angle, top to bottom of the image. The scene file may give the
    // field of view along another axis (fov_axis, scene/camera.hpp); the
    // loader converts it to this one.
    double vertical_fov_degrees = 90.0;
    int width = 0; // pixels
    int height = 0;
    // A thin lens (Mitsuba's thinlens), in scene units: the aperture's radius
    // (0: a pinhole, the eye) and the distance along the view direction from
    // the eye to the plane that is in focus (used when the radius is > 0).
    double aperture_radius = 0.0;
    double focus_distance = 1.0;
    // The pixel filter and its size in pixels: the tent's radius, or the
    // Gaussian's standard deviation (it ends at 4 of them, as Mitsuba's does);
    // the box's is fixed (one pixel). Mitsuba's defaults.
    FilterKind filter = FilterKind::Box;
    double filter_radius = 1.0; // tent
    double filter_stddev = 0.5; // gaussian
};

// The material kinds: the rows of WP_MATERIALS (kernels/wp_shared.h), with
// the kernels' values, so that flatten_scene copies a kind across as it is.
#define WP_MATERIAL_KIND_ENUMERATOR(KIND, Name, name, value, bsdf, glossy) Name = value,
enum class MaterialKind : std::uint32_t { WP_MATERIALS(WP_MATERIAL_KIND_ENUMERATOR) };
#undef WP_MATERIAL_KIND_ENUMERATOR

// The kind's name in scene files ("diffuse", "roughconductor", ...), or null
// for a value that is no kind.
const char* material_kind_name(MaterialKind kind);

// Microfacet distributions, Mitsuba's "distribution" (WP_MICROFACET_*).
enum class MicrofacetDistribution : std::uint32_t {
    Beckmann = WP_MICROFACET_BECKMANN,
    Ggx = WP_MICROFACET_GGX,
};

struct Material {
    std::string name;
    MaterialKind kind = MaterialKind::Diffuse;
    // Diffuse: the reflectance; mirror, conductors and dielectrics: Mitsuba's
    // specular_reflectance, a factor on the Fresnel term; plastic: its
    // diffuse_reflectance. In [0, 1] per channel.
    glm::dvec3 reflectance{0.0};
    // Radiance emitted from the front face (the side the right-handed winding
    // normal points to; a sphere's outside). Any material kind may emit.
    glm::dvec3 emission{0.0};
    // Conductors: the complex index of refraction eta + i k per channel.
    // Mitsuba's material "none" is eta 0, k 1: reflectance 1 at every angle.
    // `metal` names the table row the values came from ("Au", ...; empty when
    // given as numbers), for messages and the export.
    glm::dvec3 eta{0.0};
    glm::dvec3 k{1.0};
    std::string metal{};
    // Rough conductors: the microfacet distribution and its roughness along
    // the tangent (u) and bitangent (v); equal for an isotropic surface.
    MicrofacetDistribution distribution = MicrofacetDistribution::Beckmann;
    double alpha_u = 0.1;
    double alpha_v = 0.1;
    // Dielectrics: the indices of refraction inside and outside (Mitsuba's
    // int_ior and ext_ior, defaults BK7 glass and air; the outside is the
    // front side), and specular_transmittance, a factor on the refracted
    // light in [0, 1] per channel.
    double int_ior = 1.5046;
    double ext_ior = 1.000277;
    glm::dvec3 transmittance{1.0};
    // Plastic: the coating's specular_reflectance in [0, 1] per channel, and
    // Mitsuba's `nonlinear` (light the coating reflects back into the base
    // scatters there again, saturating colours).
    glm::dvec3 specular{1.0};
    bool nonlinear = false;
    // Textured parameters: 0, the constant above; k + 1, Scene::textures[k]
    // in its place (reflectance, specular, transmittance, alpha_u, alpha_v;
    // a roughness takes the texture's luminance, as Mitsuba does).
    std::uint32_t reflectance_texture = 0;
    std::uint32_t specular_texture = 0;
    std::uint32_t transmittance_texture = 0;
    std::uint32_t alpha_u_texture = 0;
    std::uint32_t alpha_v_texture = 0;

    bool is_textured() const {
        return reflectance_texture || specular_texture || transmittance_texture ||
               alpha_u_texture || alpha_v_texture;
    }

    bool is_emissive() const { return emission.x > 0.0 || emission.y > 0.0 || emission.z > 0.0; }

    // Every value that changes how the material renders (not its name), for
    // the checkpoint's scene hash (render/checkpoint.cpp); a static_assert checks
    // at compile time that no member is left out (scene/material.cpp).
    auto rendered_fields() const {
        return std::tie(kind, reflectance, emission, eta, k, distribution, alpha_u, alpha_v,
                        int_ior, ext_ior, transmittance, specular, nonlinear, reflectance_texture,
                        specular_texture, transmittance_texture, alpha_u_texture, alpha_v_texture);
    }
};

struct Sphere {
    glm::dvec3 center{0.0};
    double radius = 1.0;
    std::uint32_t material = 0;
};

// Shapes defined once and placed many times (Mitsuba's shapegroup): the
// group's triangles in its own object space. Only triangles (meshes, quads,
// ...): no spheres, and no emitting material (Mitsuba refuses emitters in a
// shape group; the loaders do too).
struct ShapeGroup {
    std::string name; // its id, for messages and the export
    TriangleList triangles;
};

// One placement of a shape group (Mitsuba's instance): the group's triangles
// mapped by to_world, an invertible affine map (its last row 0 0 0 1). A map
// with a negative determinant mirrors the group; the front faces stay on the
// side of the object normals mapped by the inverse transpose, as Mitsuba's
// instances keep them (kernels/instance.h).
struct Instance {
    std::uint32_t group = 0; // index into Scene::shape_groups
    glm::dmat4 to_world{1.0};
};

// The emitters that are not emitting surfaces, Mitsuba 3's plugins of the
// same names (docs/lights-and-camera.md), with the kernels' values
// (WP_EMITTER_*, kernels/wp_shared.h).
enum class EmitterKind : std::uint32_t {
    Point = WP_EMITTER_POINT,
    Spot = WP_EMITTER_SPOT,
    Directional = WP_EMITTER_DIRECTIONAL,
    Constant = WP_EMITTER_CONSTANT,
    Envmap = WP_EMITTER_ENVMAP,
};

// The kind's name in scene files ("point", ...), or null for no kind.
const char* emitter_kind_name(EmitterKind kind);

struct Emitter {
    EmitterKind kind = EmitterKind::Point;
    // point, spot: where it is
    glm::dvec3 position{0.0};
    // spot: the unit axis it shines along; directional: the unit direction
    // its light travels (Mitsuba's `direction`)
    glm::dvec3 direction{0.0, 0.0, 1.0};
    // rgb, >= 0: point and spot, `intensity` (W/sr); directional,
    // `irradiance` (W/m^2); constant, `radiance`; envmap, its `scale` (the
    // same in every channel)
    glm::dvec3 value{1.0};
    // spot, degrees: where the light ends, and where its linear falloff
    // starts (Mitsuba's defaults: 20, and 3/4 of the cutoff)
    double cutoff_angle = 20.0;
    double beam_width = 15.0;
    // envmap: its to_world, a rotation (the map's +y is its up), the image
    // file as the scene names it and as it was opened, and the decoded
    // image (kernels/lights/envmap.h has the conventions). The image is
    // shared: a scene is copied, its texels are not.
    glm::dmat3 to_world{1.0};
    std::string filename;
    std::string path;
    std::shared_ptr<const TextureImage> image;

    // An envmap's image enters the checkpoint hash by its texels, not here.
    auto rendered_fields() const {
        return std::tie(kind, position, direction, value, cutoff_angle, beam_width, to_world);
    }
};

// The environment among a scene's emitters (constant or envmap: at most one),
// or null.
const Emitter* find_environment(const std::vector<Emitter>& emitters);

struct Scene {
    std::string source; // file name the scene came from, for messages
    // The other files it read (its meshes), as opened, in order: outputs
    // must not overwrite any of them (app/commands.hpp).
    std::vector<std::string> files;
    Camera camera;
    std::vector<Material> materials;
    TriangleList triangles; // quads and meshes are split into triangles (meshes held indexed)
    std::vector<Sphere> spheres;
    std::vector<ShapeGroup> shape_groups; // shared meshes, placed by `instances`
    std::vector<Instance> instances;
    std::vector<Texture> textures; // named by materials' *_texture
    std::vector<Emitter> emitters; // point, spot, directional, constant, envmap: one environment
    // Mitsuba's path integrator's hide_emitters: what emits is black where the
    // camera sees it directly (a light's surface, the environment), and lights
    // as before everywhere else, reflections included. The renderer leaves
    // out the camera path type (WP_PATH_TYPE_CAMERA).
    bool hide_emitters = false;
    // Mitsuba's path integrator's max_depth and rr_depth, as a Mitsuba file
    // gives them (docs/mitsuba-import.md, "max_depth"); a JSON scene has
    // neither. max_depth is the longest path in edges, the camera ray
    // included (-1: unlimited), rendered with that meaning
    // (DepthRule::PathLength) unless the command line gives --max-depth;
    // with a Mitsuba file --max-depth has that meaning too (mitsuba_depths).
    // rr_depth is wavepath's roulette_depth (0: the file gives none).
    bool mitsuba_depths = false;
    int max_depth = -1;
    std::uint32_t rr_depth = 0;
    std::vector<std::string> warnings; // e.g. skipped zero-area triangles
};

// The triangles of the plain shapes and of every shape group (not the
// instances' copies, which are never made): what the material, normal and
// texture features of the kernels depend on.
template <typename F> void for_each_defined_triangle(const Scene& scene, F&& f) {
    for (const Triangle& t : scene.triangles)
        f(t);
    for (const ShapeGroup& g : scene.shape_groups)
        for (const Triangle& t : g.triangles)
            f(t);
}

// Whether some sphere has an emissive material (a sphere light, sampled by
// the cone it subtends: kernels/lights/sphere.h).
bool has_sphere_lights(const Scene& scene);

// Whether the scene has lights other than emissive triangles: emitters or
// sphere lights. Next-event estimation through mirrors and shadow culling
// are for triangle lights alone (render/device_scene.cpp).
bool has_lights_besides_triangles(const Scene& scene);

} // namespace wp
