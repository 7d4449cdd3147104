#include "scene/validate.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "scene/instancing.hpp"
#include "scene/scene_box.hpp"

namespace wp {

bool is_zero_area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a;
    const glm::dvec3 e2 = c - a;
    const glm::dvec3 e3 = c - b;
    const double longest2 = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
    const double twice_area = glm::length(glm::cross(e1, e2));
    return twice_area == 0.0 || twice_area <= scene_limits::zero_area_relative * longest2;
}

bool is_rotation(const glm::dmat3& m) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (!(std::abs(glm::dot(m[i], m[j]) - (i == j ? 1.0 : 0.0)) <= 1e-6))
                return false;
    return glm::dot(glm::cross(m[0], m[1]), m[2]) > 0.0;
}

bool view_direction_is_degenerate(const glm::dvec3& eye, const glm::dvec3& look_at) {
    const double d = glm::length(look_at - eye);
    const double scale = std::max(glm::length(eye), glm::length(look_at));
    return d == 0.0 || d <= scene_limits::eye_look_at_relative * scale;
}

bool up_is_parallel(const glm::dvec3& eye, const glm::dvec3& look_at, const glm::dvec3& up) {
    const glm::dvec3 d = look_at - eye;
    const double c = glm::length(glm::cross(d, up));
    return c == 0.0 || c <= scene_limits::up_parallel_relative * glm::length(d) * glm::length(up);
}

namespace {

std::string fmt(double x) {
    std::array<char, 64> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
    return std::string(buf.data(), res.ptr);
}

// Three significant digits, for derived quantities (sizes, ratios).
std::string fmt3(double x) {
    std::array<char, 64> buf{};
    const auto res =
        std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::general, 3);
    return std::string(buf.data(), res.ptr);
}

class Checker {
  public:
    explicit Checker(const Scene& scene) : scene_(scene) {}

    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw SceneError(scene_.source + ": " + field + ": " + problem);
    }

    void number(double x, const std::string& field, double lo, double hi) const {
        if (!std::isfinite(x))
            fail(field, "must be finite, got " + fmt(x));
        if (x < lo || x > hi)
            fail(field, "must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(x));
    }

    // In (0, hi].
    void positive(double x, const std::string& field, double hi) const {
        if (!std::isfinite(x))
            fail(field, "must be finite, got " + fmt(x));
        if (!(x > 0.0) || x > hi)
            fail(field, "must be in (0, " + fmt(hi) + "], got " + fmt(x));
    }

    void vec(const glm::dvec3& v, const std::string& field, double lo, double hi) const {
        for (int i = 0; i < 3; ++i)
            number(v[i], field + "[" + std::to_string(i) + "]", lo, hi);
    }

    void point(const glm::dvec3& v, const std::string& field) const {
        vec(v, field, -scene_limits::max_coordinate, scene_limits::max_coordinate);
    }

    void material_index(std::uint32_t m, const std::string& field) const {
        if (m >= scene_.materials.size())
            fail(field, "material index " + std::to_string(m) + " out of range (" +
                            std::to_string(scene_.materials.size()) + " materials)");
    }

    void run() const {
        const Camera& c = scene_.camera;
        point(c.eye, "camera.eye");
        point(c.look_at, "camera.look_at");
        point(c.up, "camera.up");
        if (!(c.vertical_fov_degrees > 0.0 && c.vertical_fov_degrees < 180.0))
            fail("camera.vertical_fov_degrees",
                 "must be between 0 and 180 (exclusive), got " + fmt(c.vertical_fov_degrees));
        if (c.width < 1 || c.width > scene_limits::max_resolution)
            fail("camera.width", "must be in [1, 16384], got " + std::to_string(c.width));
        if (c.height < 1 || c.height > scene_limits::max_resolution)
            fail("camera.height", "must be in [1, 16384], got " + std::to_string(c.height));
        if (view_direction_is_degenerate(c.eye, c.look_at))
            fail("camera.look_at", "must differ from camera.eye by more than 1e-9 of their "
                                   "distance from the origin (there is no usable view direction)");
        if (up_is_parallel(c.eye, c.look_at, c.up))
            fail("camera.up", "is zero or parallel to the view direction");
        if (!(c.aperture_radius >= 0.0 && c.aperture_radius <= scene_limits::max_coordinate))
            fail("camera.aperture_radius", "must be in [0, 1e30], got " + fmt(c.aperture_radius));
        if (!(c.focus_distance > 0.0 && c.focus_distance <= scene_limits::max_coordinate))
            fail("camera.focus_distance", "must be in (0, 1e30], got " + fmt(c.focus_distance));
        if (static_cast<wp_uint>(c.filter) >= WP_FILTER_KIND_COUNT)
            fail("camera.filter", "unknown filter kind");
        for (const auto& [value, field] : {std::pair{c.filter_radius, "camera.filter_radius"},
                                           std::pair{c.filter_stddev, "camera.filter_stddev"}})
            if (!(value > 0.0 && value <= scene_limits::max_filter_size))
                fail(field, "must be in (0, 64] pixels, got " + fmt(value));

        for (std::size_t i = 0; i < scene_.materials.size(); ++i) {
            const Material& m = scene_.materials[i];
            const std::string f = "materials[" + std::to_string(i) + "] ('" + m.name + "')";
            if (!material_kind_name(m.kind))
                fail(f + ".kind", "unknown material kind");
            vec(m.reflectance, f + ".reflectance", 0.0, 1.0);
            if (m.kind == MaterialKind::Emitter && m.reflectance != glm::dvec3(0.0))
                fail(f + ".reflectance", "must be 0 for an emitter");
            vec(m.emission, f + ".emission", 0.0, scene_limits::max_radiance);
            // Every kind's own parameters (no default: a new kind must say).
            switch (m.kind) {
            case MaterialKind::Diffuse:
            case MaterialKind::Mirror:
            case MaterialKind::Emitter:
                break;
            case MaterialKind::RoughConductor:
                if (m.distribution != MicrofacetDistribution::Beckmann &&
                    m.distribution != MicrofacetDistribution::Ggx)
                    fail(f + ".distribution", "unknown microfacet distribution");
                positive(m.alpha_u, f + ".alpha_u", scene_limits::max_alpha);
                positive(m.alpha_v, f + ".alpha_v", scene_limits::max_alpha);
                [[fallthrough]];
            case MaterialKind::Conductor:
                vec(m.eta, f + ".eta", 0.0, scene_limits::max_index);
                vec(m.k, f + ".k", 0.0, scene_limits::max_index);
                break;
            case MaterialKind::RoughDielectric:
            case MaterialKind::RoughPlastic:
                if (m.distribution != MicrofacetDistribution::Beckmann &&
                    m.distribution != MicrofacetDistribution::Ggx)
                    fail(f + ".distribution", "unknown microfacet distribution");
                positive(m.alpha_u, f + ".alpha_u", scene_limits::max_alpha);
                positive(m.alpha_v, f + ".alpha_v", scene_limits::max_alpha);
                // The coating's tables are integrated for one roughness.
                if (m.kind == MaterialKind::RoughPlastic && m.alpha_u != m.alpha_v)
                    fail(f + ".alpha_v", "must equal alpha_u (roughplastic is isotropic)");
                [[fallthrough]];
            case MaterialKind::Plastic:
                if (m.kind == MaterialKind::Plastic || m.kind == MaterialKind::RoughPlastic)
                    vec(m.specular, f + ".specular", 0.0, 1.0);
                [[fallthrough]];
            case MaterialKind::Dielectric:
            case MaterialKind::ThinDielectric:
                positive(m.int_ior, f + ".int_ior", scene_limits::max_index);
                positive(m.ext_ior, f + ".ext_ior", scene_limits::max_index);
                vec(m.transmittance, f + ".transmittance", 0.0, 1.0);
                break;
            }
            for (const auto& [texture, field] :
                 {std::pair{m.reflectance_texture, ".reflectance_texture"},
                  std::pair{m.specular_texture, ".specular_texture"},
                  std::pair{m.transmittance_texture, ".transmittance_texture"},
                  std::pair{m.alpha_u_texture, ".alpha_u_texture"},
                  std::pair{m.alpha_v_texture, ".alpha_v_texture"}})
                if (texture > scene_.textures.size())
                    fail(f + field, "texture " + std::to_string(texture) + " out of range (" +
                                        std::to_string(scene_.textures.size()) + " textures)");
            // next-event estimation through mirrors takes one colour (mirror_light.h)
            if (m.kind == MaterialKind::Mirror && m.reflectance_texture)
                fail(f + ".reflectance_texture", "a mirror's reflectance cannot be a texture");
        }

        for (std::size_t i = 0; i < scene_.textures.size(); ++i) {
            const Texture& t = scene_.textures[i];
            const std::string f = "textures[" + std::to_string(i) + "]";
            if (!texture_kind_name(t.kind))
                fail(f + ".kind", "unknown texture kind");
            vec(t.color0, f + ".color0", 0.0, scene_limits::max_radiance);
            vec(t.color1, f + ".color1", 0.0, scene_limits::max_radiance);
            vec(t.to_u, f + ".to_u", -scene_limits::max_coordinate, scene_limits::max_coordinate);
            vec(t.to_v, f + ".to_v", -scene_limits::max_coordinate, scene_limits::max_coordinate);
            if (t.kind == TextureKind::Bitmap &&
                (!t.image || t.image->width == 0 || t.image->height == 0 ||
                 t.image->texels.size() !=
                     std::size_t{t.image->width} * t.image->height *
                         (t.image->encoding == TexelEncoding::Float32 ? 3 : 1)))
                fail(f + ".image", "a bitmap without texels of its size");
        }

        for (std::size_t i = 0; i < scene_.triangles.size(); ++i) {
            const Triangle& t = scene_.triangles[i];
            if (passes(t))
                continue;
            const std::string f = "triangles[" + std::to_string(i) + "]";
            for (int k = 0; k < 3; ++k)
                point(t.v[static_cast<std::size_t>(k)], f + ".v[" + std::to_string(k) + "]");
            material_index(t.material, f + ".material");
            if (is_zero_area(t.v[0], t.v[1], t.v[2])) {
                extent(); // a scene too far from the origin loses its triangles' areas
                fail(f, "zero-area triangle (the loader skips these)");
            }
        }

        for (std::size_t i = 0; i < scene_.spheres.size(); ++i) {
            const Sphere& s = scene_.spheres[i];
            const std::string f = "spheres[" + std::to_string(i) + "]";
            point(s.center, f + ".center");
            if (!std::isfinite(s.radius) || s.radius <= 0.0 ||
                s.radius > scene_limits::max_coordinate)
                fail(f + ".radius", "must be positive and at most 1e30, got " + fmt(s.radius));
            material_index(s.material, f + ".material");
        }

        int environments = 0;
        for (std::size_t i = 0; i < scene_.emitters.size(); ++i) {
            const Emitter& e = scene_.emitters[i];
            const std::string f = "emitters[" + std::to_string(i) + "]";
            if (!emitter_kind_name(e.kind))
                fail(f + ".kind", "unknown emitter kind");
            vec(e.value, f + ".value", 0.0, scene_limits::max_radiance);
            point(e.position, f + ".position");
            const double length = glm::length(e.direction);
            if (!(std::abs(length - 1.0) < 1e-9))
                fail(f + ".direction", "must be a unit vector, got length " + fmt(length));
            if (e.kind == EmitterKind::Spot) {
                if (!(e.cutoff_angle > 0.0 && e.cutoff_angle <= 180.0))
                    fail(f + ".cutoff_angle",
                         "must be in (0, 180] degrees, got " + fmt(e.cutoff_angle));
                if (!(e.beam_width >= 0.0 && e.beam_width <= 180.0))
                    fail(f + ".beam_width",
                         "must be in [0, 180] degrees, got " + fmt(e.beam_width));
            }
            if (e.kind == EmitterKind::Envmap) {
                if (!e.image || e.image->width == 0 || e.image->height == 0)
                    fail(f + ".filename", "the envmap has no image");
                if (!is_rotation(e.to_world))
                    fail(f + ".to_world", "must be a rotation (an environment map is only "
                                          "turned: no scale, shear or mirror)");
            }
            if ((e.kind == EmitterKind::Constant || e.kind == EmitterKind::Envmap) &&
                ++environments > 1)
                fail(f, "a second environment (constant or envmap emitter): a scene has at most "
                        "one");
        }

        for (std::size_t g = 0; g < scene_.shape_groups.size(); ++g) {
            const ShapeGroup& group = scene_.shape_groups[g];
            for (std::size_t i = 0; i < group.triangles.size(); ++i) {
                const Triangle& t = group.triangles[i];
                if (passes(t))
                    continue;
                const std::string f = "shape_groups[" + std::to_string(g) + "] ('" + group.name +
                                      "').triangles[" + std::to_string(i) + "]";
                for (int k = 0; k < 3; ++k)
                    point(t.v[static_cast<std::size_t>(k)], f + ".v[" + std::to_string(k) + "]");
                material_index(t.material, f + ".material");
                fail(f, "zero-area triangle (the loader skips these)");
            }
            if (const std::string problem = group_material_problem(group, scene_.materials);
                !problem.empty())
                fail("shape_groups[" + std::to_string(g) + "]", problem);
        }
        for (std::size_t i = 0; i < scene_.instances.size(); ++i) {
            const Instance& instance = scene_.instances[i];
            const std::string f = "instances[" + std::to_string(i) + "]";
            if (instance.group >= scene_.shape_groups.size())
                fail(f + ".group", "shape group index " + std::to_string(instance.group) +
                                       " out of range (" +
                                       std::to_string(scene_.shape_groups.size()) + " groups)");
            if (const std::string problem = instance_transform_problem(instance.to_world);
                !problem.empty())
                fail(f + ".to_world", problem);
        }
        // Instanced hits are numbered past the plain primitives in 32 bits
        // (kernels/wp_shared.h, WpInstance).
        const std::uint64_t numbered = instanced_triangle_count(scene_) + scene_.triangles.size() +
                                       scene_.spheres.size() + scene_.instances.size();
        if (numbered >= 0xffffffffull)
            fail("instances", "the instances place " + std::to_string(numbered) +
                                  " triangles; the device numbers at most 2^32 - 2 primitives");

        if (scene_.triangles.empty() && scene_.spheres.empty() && scene_.instances.empty())
            fail("shapes", "the scene has no shapes");
        extent();
    }

  private:
    // The scene's size and distance from the origin, against what double
    // input and float32 rendering can resolve (validate.hpp).
    void extent() const {
        const SceneBox box = scene_box(scene_);
        const double size = box.size(), distance = box.largest_coordinate();
        if (!std::isfinite(size) || !std::isfinite(distance))
            return; // a non-finite coordinate, which its own check names
        if (!(size >= scene_limits::min_scene_size))
            fail("shapes", "the scene's size " + fmt3(size) +
                               " (its box's longest side) is below " +
                               fmt3(scene_limits::min_scene_size) +
                               ", the smallest whose areas squared double holds");
        if (distance > scene_limits::max_distance_to_size * size)
            fail("shapes", "the scene lies " + fmt3(distance) + " from the origin, " +
                               fmt3(distance / size) + " times its size " + fmt3(size) +
                               "; at most 2^29 = 5.4e8 times its size can be rendered (its "
                               "coordinates would need more than double's 16 digits)");
    }

    // The checks below, without building the field names that only a failure
    // needs: for a mesh of a million triangles the names took most of the
    // load time.
    bool passes(const Triangle& t) const {
        for (const glm::dvec3& p : t.v)
            for (int i = 0; i < 3; ++i)
                if (!(std::abs(p[i]) <= scene_limits::max_coordinate)) // also NaN
                    return false;
        return t.material < scene_.materials.size() && !is_zero_area(t.v[0], t.v[1], t.v[2]);
    }

    const Scene& scene_;
};

} // namespace

bool has_emitter(const Scene& scene) {
    for (const Emitter& e : scene.emitters) // a point, spot, sun or sky that is not black
        if (e.value.x > 0.0 || e.value.y > 0.0 || e.value.z > 0.0)
            return true;
    for (const Triangle& t : scene.triangles)
        if (t.material < scene.materials.size() && scene.materials[t.material].is_emissive())
            return true;
    return has_sphere_lights(scene);
}

void validate_scene(const Scene& scene) {
    Checker(scene).run();
}

} // namespace wp
