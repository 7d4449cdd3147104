#include "scene/load.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "image/image.hpp"
#include "image/texture_image.hpp"
#include "scene/camera.hpp"
#include "scene/instancing.hpp"
#include "scene/json_reader.hpp"
#include "scene/material.hpp"
#include "scene/mesh.hpp"
#include "scene/mitsuba/load_mitsuba.hpp"
#include "scene/texture.hpp"
#include "scene/transform_reader.hpp"
#include "scene/validate.hpp"
#include "util/file.hpp"

namespace wp {

namespace {

using json::describe;
using json::Json;
using json::number_text;
using json::one_line;
using json::pointer_text;
using json::shorten;
using Ptr = json::Pointer;

// A computed value, to 4 significant digits.
std::string fmt4(double x) {
    std::array<char, 64> buf{};
    const auto res =
        std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::general, 4);
    return std::string(buf.data(), res.ptr);
}

// ---------------------------------------------------------------------------
// DOM -> Scene, validating every field.

enum class Range { Coordinate, Reflectance, Radiance, Index };

// A json::Reader that knows scenes: the fields, their ranges and how they
// become a wp::Scene. Mesh files are found relative to `folder`, the scene
// file's folder.
class SceneReader : private json::Reader {
  public:
    SceneReader(const std::string& source, std::filesystem::path folder)
        : json::Reader(source), folder_(std::move(folder)) {
        scene_.source = source;
    }

    Scene read(const Json& root) {
        const Ptr top;
        expect_object(root, top, "a scene object with camera, materials and shapes");
        check_keys(root, top, {"camera", "materials", "shapes", "emitters", "description"});
        if (const auto it = root.find("description"); it != root.end())
            expect_string(*it, top / "description");
        read_camera(require(root, top, "camera"), top / "camera");
        read_materials(require(root, top, "materials"), top / "materials");
        read_shapes(require(root, top, "shapes"), top / "shapes");
        if (const auto it = root.find("emitters"); it != root.end())
            read_emitters(*it, top / "emitters");
        return std::move(scene_);
    }

  private:
    void check_range(double x, const Ptr& p, Range range) const {
        switch (range) {
        case Range::Coordinate:
            if (std::abs(x) > scene_limits::max_coordinate)
                fail(p, "magnitude too large for float32 rendering (limit 1e30), got " +
                            number_text(x));
            break;
        case Range::Reflectance:
            if (x < 0.0 || x > 1.0)
                fail(p, "reflectance must be in [0, 1], got " + number_text(x));
            break;
        case Range::Index: // a conductor's eta or k
            if (x < 0.0)
                fail(p, "must not be negative, got " + number_text(x));
            if (x > scene_limits::max_index)
                fail(p, "must be at most 1e4, got " + number_text(x));
            break;
        case Range::Radiance:
            if (x < 0.0)
                fail(p, "must not be negative, got " + number_text(x));
            if (x > scene_limits::max_radiance)
                fail(p, "must be at most 1e30 (float32 range), got " + number_text(x));
            break;
        }
    }

    glm::dvec3 vec3(const Json& v, const Ptr& p, Range range) const {
        if (!v.is_array() || v.size() != 3)
            fail(p, "expected an array of 3 numbers, got " + describe(v));
        glm::dvec3 r;
        for (std::size_t i = 0; i < 3; ++i) {
            const double x = number(v[i], p / i);
            check_range(x, p / i, range);
            r[static_cast<glm::length_t>(i)] = x;
        }
        return r;
    }

    // An array of points; exact_count 0 means "at least one".
    std::vector<glm::dvec3> points(const Json& v, const Ptr& p, std::size_t exact_count) const {
        if (!v.is_array())
            fail(p, "expected an array of points ([x, y, z] arrays), got " + describe(v));
        if (exact_count != 0 && v.size() != exact_count)
            fail(p, "expected exactly " + std::to_string(exact_count) +
                        " points ([x, y, z] arrays), got " + describe(v));
        if (v.empty())
            fail(p, "must contain at least one point");
        std::vector<glm::dvec3> r;
        r.reserve(v.size());
        for (std::size_t i = 0; i < v.size(); ++i)
            r.push_back(vec3(v[i], p / i, Range::Coordinate));
        return r;
    }

    // --- camera ---------------------------------------------------------------

    void read_camera(const Json& cam, const Ptr& p) {
        expect_object(cam, p, "an object");
        check_keys(cam, p,
                   {"eye", "look_at", "direction", "up", "fov", "fov_axis", "resolution",
                    "aperture_radius", "focus_distance", "filter"});
        Camera& c = scene_.camera;
        c.eye = vec3(require(cam, p, "eye"), p / "eye", Range::Coordinate);

        const bool has_look_at = cam.contains("look_at");
        const bool has_direction = cam.contains("direction");
        if (has_look_at && has_direction)
            fail(p / "direction", "give either 'look_at' or 'direction', not both");
        if (!has_look_at && !has_direction)
            fail(p / "look_at", "missing required field 'look_at' (or give 'direction')");
        if (has_look_at) {
            c.look_at = vec3(cam.at("look_at"), p / "look_at", Range::Coordinate);
            if (view_direction_is_degenerate(c.eye, c.look_at))
                fail(p / "look_at", "must differ from eye by more than 1e-9 of their distance from "
                                    "the origin (there is no usable view direction)");
        } else {
            const glm::dvec3 d = vec3(cam.at("direction"), p / "direction", Range::Coordinate);
            if (d == glm::dvec3(0.0))
                fail(p / "direction", "must not be the zero vector");
            c.look_at = c.eye + d;
            if (view_direction_is_degenerate(c.eye, c.look_at))
                fail(p / "direction", "too short to be resolved at the eye's distance from the "
                                      "origin (give a longer direction)");
        }
        const char* dir_name = has_look_at ? "look_at - eye" : "direction";

        c.up = vec3(require(cam, p, "up"), p / "up", Range::Coordinate);
        if (c.up == glm::dvec3(0.0))
            fail(p / "up", "must not be the zero vector");
        if (up_is_parallel(c.eye, c.look_at, c.up))
            fail(p / "up", std::string("is parallel to the view direction (") + dir_name +
                               "): the image's orientation is undefined");

        FovAxis axis = FovAxis::Y;
        if (auto it = cam.find("fov_axis"); it != cam.end()) {
            const std::string& name = expect_string(*it, p / "fov_axis");
            const std::optional<FovAxis> a = fov_axis_from_name(name);
            if (!a)
                fail(p / "fov_axis", "unknown fov_axis '" + shorten(name, 40) + "' (expected " +
                                         fov_axis_names() + ")");
            axis = *a;
        }
        const Ptr pf = p / "fov";
        const double fov = number(require(cam, p, "fov"), pf);
        if (!(fov > 0.0 && fov < 180.0))
            fail(pf, std::string(axis == FovAxis::Y ? "vertical field of view"
                                                    : "field of view along fov_axis '" +
                                                          std::string(fov_axis_name(axis)) + "'") +
                         " must be between 0 and 180 degrees (exclusive), got " + number_text(fov));

        const Ptr pr = p / "resolution";
        const Json& res = require(cam, p, "resolution");
        if (!res.is_array() || res.size() != 2)
            fail(pr, "expected an array of 2 integers [width, height], got " + describe(res));
        std::array<int, 2> wh{};
        for (std::size_t i = 0; i < 2; ++i) {
            const double x = whole_number(res[i], pr / i);
            if (x < 1.0)
                fail(pr / i, "must be a positive number of pixels, got " + number_text(x));
            if (x > scene_limits::max_resolution)
                fail(pr / i, "must be at most 16384 pixels, got " + number_text(x));
            wh[i] = static_cast<int>(x);
        }
        c.width = wh[0];
        c.height = wh[1];
        // Needs the resolution: the axes are related by the aspect ratio.
        c.vertical_fov_degrees = vertical_fov_degrees(fov, axis, c.width, c.height);

        read_lens(cam, p);
        if (auto it = cam.find("filter"); it != cam.end())
            read_filter(*it, p / "filter");
    }

    // A thin lens: aperture_radius >= 0 (0, the default, is a pinhole), and
    // with a positive one a focus_distance > 0; both in scene units.
    void read_lens(const Json& cam, const Ptr& p) {
        Camera& c = scene_.camera;
        if (auto it = cam.find("aperture_radius"); it != cam.end()) {
            c.aperture_radius = number(*it, p / "aperture_radius");
            if (c.aperture_radius < 0.0)
                fail(p / "aperture_radius", "must not be negative (0 is a pinhole), got " +
                                                number_text(c.aperture_radius));
            check_range(c.aperture_radius, p / "aperture_radius", Range::Coordinate);
        }
        if (auto it = cam.find("focus_distance"); it != cam.end()) {
            c.focus_distance = number(*it, p / "focus_distance");
            if (!(c.focus_distance > 0.0))
                fail(p / "focus_distance",
                     "must be positive, got " + number_text(c.focus_distance));
            check_range(c.focus_distance, p / "focus_distance", Range::Coordinate);
        } else if (c.aperture_radius > 0.0) {
            fail(p / "focus_distance",
                 "missing required field 'focus_distance' (a lens with aperture_radius > 0 "
                 "focuses at that distance)");
        }
    }

    // "filter": a name ("tent"), or an object with its type and size:
    // {"type": "tent", "radius": 1} or {"type": "gaussian", "stddev": 0.5}
    // (Mitsuba's rfilter plugins and their defaults).
    void read_filter(const Json& f, const Ptr& p) {
        Camera& c = scene_.camera;
        const bool is_object = f.is_object();
        const Ptr pt = is_object ? p / "type" : p;
        const std::string& name =
            is_object ? expect_string(require(f, p, "type"), pt) : expect_string(f, p);
        const std::optional<FilterKind> kind = filter_kind_from_name(name);
        if (!kind)
            fail(pt, "unknown filter '" + shorten(name, 40) + "' (expected " + filter_kind_names() +
                         ")");
        c.filter = *kind;
        if (!is_object)
            return;
        const char* size = c.filter == FilterKind::Tent       ? "radius"
                           : c.filter == FilterKind::Gaussian ? "stddev"
                                                              : nullptr;
        if (size)
            check_keys(f, p, {"type", size});
        else
            check_keys(f, p, {"type"});
        if (!size)
            return;
        auto it = f.find(size);
        if (it == f.end())
            return;
        const double x = number(*it, p / size);
        if (!(x > 0.0 && x <= scene_limits::max_filter_size))
            fail(p / size, "must be positive and at most " +
                               number_text(scene_limits::max_filter_size) + " pixels, got " +
                               number_text(x));
        (c.filter == FilterKind::Tent ? c.filter_radius : c.filter_stddev) = x;
    }

    // --- materials ------------------------------------------------------------

    void read_materials(const Json& mats, const Ptr& p) {
        expect_object(mats, p, "an object mapping material names to materials");
        if (mats.empty())
            fail(p, "must define at least one material");
        for (const auto& [name, m] : mats.items()) {
            const Ptr pm = p / name;
            expect_object(m, pm, "a material object");
            const std::string& type = expect_string(require(m, pm, "type"), pm / "type");
            const std::optional<MaterialKind> kind = material_kind_from_name(type);
            // Mitsuba's wrapper has nothing to do here: every reflecting kind
            // reflects alike on both sides (docs/materials.md), so say so
            // rather than only that the type is unknown.
            if (type == "twosided")
                fail(pm / "type", "wavepath's reflecting materials are two-sided already: give "
                                  "the material itself (e.g. \"type\": \"roughplastic\")");
            if (!kind)
                fail(pm / "type", "unknown material type '" + shorten(type, 40) + "' (expected " +
                                      material_kind_names() + ")");
            Material mat;
            mat.name = name;
            mat.kind = *kind;
            read_material(m, pm, mat);
            material_index_.emplace(name, static_cast<std::uint32_t>(scene_.materials.size()));
            scene_.materials.push_back(std::move(mat));
        }
    }

    // The parameters of one material of kind mat.kind, named as Mitsuba 3's
    // plugins name them (docs/scene-format.md). Every kind of WP_MATERIALS has
    // its case: the switch has no default, so the compiler names a missing one.
    void read_material(const Json& m, const Ptr& pm, Material& mat) {
        switch (mat.kind) {
        case MaterialKind::Diffuse:
        case MaterialKind::Mirror:
            check_keys(m, pm, {"type", "reflectance", "emission"});
            if (mat.kind == MaterialKind::Mirror && require(m, pm, "reflectance").is_object())
                fail(pm / "reflectance",
                     "a mirror's reflectance cannot be a texture (next-event estimation through "
                     "mirrors takes one colour); use a conductor with a textured "
                     "specular_reflectance");
            mat.reflectance =
                colour(require(m, pm, "reflectance"), pm / "reflectance", mat.reflectance_texture);
            read_emission(m, pm, mat);
            return;
        case MaterialKind::Emitter:
            check_keys(m, pm, {"type", "radiance"});
            mat.reflectance = glm::dvec3(0.0);
            mat.emission = vec3(require(m, pm, "radiance"), pm / "radiance", Range::Radiance);
            // one_line: the pointer holds the material's name as the file spells it.
            if (!mat.is_emissive())
                scene_.warnings.push_back(one_line(pointer_text(pm / "radiance") +
                                                   ": emitter with zero radiance emits nothing"));
            return;
        case MaterialKind::Conductor:
            check_keys(m, pm, {"type", "material", "eta", "k", "specular_reflectance", "emission"});
            read_conductor(m, pm, mat);
            // Mitsuba's default, material "none" without eta and k: the perfect
            // mirror, which is the mirror kind (and its next-event estimation).
            if (mat.metal == "none" && m.find("eta") == m.end() && m.find("k") == m.end() &&
                !mat.is_textured())
                mat.kind = MaterialKind::Mirror;
            return;
        case MaterialKind::RoughConductor:
            check_keys(m, pm,
                       {"type", "material", "eta", "k", "specular_reflectance", "emission",
                        "distribution", "alpha", "alpha_u", "alpha_v"});
            read_conductor(m, pm, mat);
            read_roughness(m, pm, mat);
            return;
        case MaterialKind::RoughDielectric:
            check_keys(m, pm,
                       {"type", "int_ior", "ext_ior", "specular_reflectance",
                        "specular_transmittance", "emission", "distribution", "alpha", "alpha_u",
                        "alpha_v"});
            read_dielectric(m, pm, mat);
            read_roughness(m, pm, mat);
            return;
        case MaterialKind::Plastic:
            check_keys(m, pm,
                       {"type", "int_ior", "ext_ior", "diffuse_reflectance", "specular_reflectance",
                        "nonlinear", "emission"});
            read_plastic(m, pm, mat);
            return;
        case MaterialKind::RoughPlastic:
            check_keys(m, pm,
                       {"type", "int_ior", "ext_ior", "diffuse_reflectance", "specular_reflectance",
                        "nonlinear", "emission", "distribution", "alpha", "alpha_u", "alpha_v"});
            // Mitsuba's roughplastic refuses anisotropic roughness too.
            for (const char* key : {"alpha_u", "alpha_v"})
                if (m.find(key) != m.end())
                    fail(pm / key, "roughplastic's roughness is isotropic (as in Mitsuba): give "
                                   "'alpha'");
            read_plastic(m, pm, mat);
            read_roughness(m, pm, mat);
            // Its coating's transmittance table is computed for one alpha.
            if (mat.alpha_u_texture)
                fail(pm / "alpha", "roughplastic's roughness cannot be a texture (its coating's "
                                   "transmittance table is computed once per material)");
            return;
        case MaterialKind::Dielectric:
        case MaterialKind::ThinDielectric:
            check_keys(m, pm,
                       {"type", "int_ior", "ext_ior", "specular_reflectance",
                        "specular_transmittance", "emission"});
            read_dielectric(m, pm, mat);
            return;
        }
        fail(pm / "type", "material kind without a reader"); // unreachable for valid kinds
    }

    // --- textures --------------------------------------------------------------

    // A colour parameter: [r, g, b] in [0, 1], or a texture object
    // (read_texture), whose number k + 1 goes to `texture`; the constant is
    // then the texture's mean, clamped to [0, 1] (the BSDF sees the texture,
    // the host's heuristics such as plastic's sampling weight the mean).
    glm::dvec3 colour(const Json& v, const Ptr& p, std::uint32_t& texture) {
        if (v.is_object()) {
            texture = read_texture(v, p);
            return glm::clamp(scene_.textures[texture - 1].mean(), 0.0, 1.0);
        }
        return vec3(v, p, Range::Reflectance);
    }

    // A texture object, Mitsuba's plugins and parameters (docs/materials.md,
    // "Textures"):
    //   {"type": "bitmap", "filename": "wood.png", "filter_type": "bilinear",
    //    "wrap_mode": "repeat", "raw": false, "to_uv": [transform steps]}
    //   {"type": "checkerboard", "color0": 0.4, "color1": [0.2, 0.2, 0.2],
    //    "to_uv": [...]}
    // Returns its number k + 1 in Scene::textures.
    std::uint32_t read_texture(const Json& t, const Ptr& p) {
        const std::string& type = expect_string(require(t, p, "type"), p / "type");
        const std::optional<TextureKind> kind = texture_kind_from_name(type);
        if (!kind)
            fail(p / "type", "unknown texture type '" + shorten(type, 40) + "' (expected " +
                                 texture_kind_names() + ")");
        Texture tex;
        tex.kind = *kind;
        switch (tex.kind) {
        case TextureKind::Bitmap:
            check_keys(t, p, {"type", "filename", "filter_type", "wrap_mode", "raw", "to_uv"});
            read_bitmap(t, p, tex);
            break;
        case TextureKind::Checkerboard:
            check_keys(t, p, {"type", "color0", "color1", "to_uv"});
            if (const auto it = t.find("color0"); it != t.end())
                tex.color0 = texture_colour(*it, p / "color0");
            if (const auto it = t.find("color1"); it != t.end())
                tex.color1 = texture_colour(*it, p / "color1");
            break;
        }
        if (const auto it = t.find("to_uv"); it != t.end()) {
            // Mitsuba's to_uv acts on (u, v, 0) as a 3D transform; the kernels
            // keep its rows for x and y, without z.
            const Transform to_uv = read_transform(*this, *it, p / "to_uv");
            const glm::dmat4& m = to_uv.matrix();
            tex.to_u = {m[0][0], m[1][0], m[3][0]};
            tex.to_v = {m[0][1], m[1][1], m[3][1]};
        }
        scene_.textures.push_back(std::move(tex));
        return static_cast<std::uint32_t>(scene_.textures.size());
    }

    // A checkerboard's colour: a number (grey) or [r, g, b], each >= 0.
    glm::dvec3 texture_colour(const Json& v, const Ptr& p) const {
        if (v.is_number()) {
            const double x = number(v, p);
            check_range(x, p, Range::Radiance);
            return glm::dvec3(x);
        }
        return vec3(v, p, Range::Radiance);
    }

    void read_bitmap(const Json& t, const Ptr& p, Texture& tex) {
        const Ptr pf = p / "filename";
        tex.filename = expect_string(require(t, p, "filename"), pf);
        if (tex.filename.empty())
            fail(pf, "must name an image file (PNG, JPEG, HDR, EXR, ...)");
        if (const auto it = t.find("raw"); it != t.end()) {
            if (!it->is_boolean())
                fail(p / "raw", "expected true or false, got " + describe(*it));
            tex.raw = it->get<bool>();
        }
        if (const auto it = t.find("filter_type"); it != t.end()) {
            const std::string& name = expect_string(*it, p / "filter_type");
            const std::optional<TextureFilter> filter = texture_filter_from_name(name);
            if (!filter)
                fail(p / "filter_type", "unknown filter_type '" + shorten(name, 40) +
                                            "' (expected bilinear or nearest)");
            tex.filter = *filter;
        }
        if (const auto it = t.find("wrap_mode"); it != t.end()) {
            const std::string& name = expect_string(*it, p / "wrap_mode");
            const std::optional<TextureWrap> wrap = texture_wrap_from_name(name);
            if (!wrap)
                fail(p / "wrap_mode", "unknown wrap_mode '" + shorten(name, 40) +
                                          "' (expected repeat, mirror or clamp)");
            tex.wrap = *wrap;
        }
        const std::filesystem::path path = folder_ / tex.filename;
        tex.path = path.string();
        scene_.files.push_back(tex.path);
        tex.image = load_texture_image(path, tex.raw, pf);
    }

    // Each file is decoded once, however many textures name it.
    std::shared_ptr<const TextureImage> load_texture_image(const std::filesystem::path& path,
                                                           bool raw, const Ptr& p) {
        const auto key = std::make_pair(path.lexically_normal().string(), raw);
        if (const auto it = texture_images_.find(key); it != texture_images_.end())
            return it->second;
        std::shared_ptr<const TextureImage> image;
        try {
            image = std::make_shared<const TextureImage>(read_texture_image(path, raw));
        } catch (const FileError& e) {
            fail(p, e.what());
        } catch (const ImageError& e) {
            fail(p, e.what());
        }
        texture_images_.emplace(key, image);
        return image;
    }

    void read_emission(const Json& m, const Ptr& pm, Material& mat) const {
        if (const auto it = m.find("emission"); it != m.end())
            mat.emission = vec3(*it, pm / "emission", Range::Radiance);
    }

    // Mitsuba's conductor parameters: a named metal ("material", default
    // "none": eta 0, k 1, reflectance 1) or eta and k, never both, and
    // specular_reflectance (default 1) on top.
    void read_conductor(const Json& m, const Ptr& pm, Material& mat) {
        mat.metal = "none";
        if (const auto it = m.find("material"); it != m.end()) {
            mat.metal = expect_string(*it, pm / "material");
            if (mat.metal != "none") {
                const NamedMetal* metal = find_metal(mat.metal);
                if (!metal) {
                    std::string known = "none";
                    for (const NamedMetal& n : named_metals())
                        known += std::string(", ") + n.name;
                    fail(pm / "material",
                         "unknown metal '" + shorten(mat.metal, 40) + "' (expected " + known + ")");
                }
                if (m.find("eta") != m.end() || m.find("k") != m.end())
                    fail(pm / "material", "give either a named material or eta and k, not both");
                mat.eta = metal->eta;
                mat.k = metal->k;
            }
        }
        if (const auto it = m.find("eta"); it != m.end()) {
            mat.eta = vec3(*it, pm / "eta", Range::Index);
            mat.metal.clear();
        }
        if (const auto it = m.find("k"); it != m.end()) {
            mat.k = vec3(*it, pm / "k", Range::Index);
            mat.metal.clear();
        }
        mat.reflectance = glm::dvec3(1.0);
        if (const auto it = m.find("specular_reflectance"); it != m.end())
            mat.reflectance = colour(*it, pm / "specular_reflectance", mat.reflectance_texture);
        read_emission(m, pm, mat);
    }

    // Mitsuba's dielectric parameters: int_ior and ext_ior, each a number or
    // a name of Mitsuba's table (defaults "bk7" and "air"), and
    // specular_reflectance and specular_transmittance (default 1).
    void read_dielectric(const Json& m, const Ptr& pm, Material& mat) {
        if (const auto it = m.find("int_ior"); it != m.end())
            mat.int_ior = ior(*it, pm / "int_ior");
        if (const auto it = m.find("ext_ior"); it != m.end())
            mat.ext_ior = ior(*it, pm / "ext_ior");
        mat.reflectance = glm::dvec3(1.0);
        if (const auto it = m.find("specular_reflectance"); it != m.end())
            mat.reflectance = colour(*it, pm / "specular_reflectance", mat.reflectance_texture);
        if (const auto it = m.find("specular_transmittance"); it != m.end())
            mat.transmittance =
                colour(*it, pm / "specular_transmittance", mat.transmittance_texture);
        read_emission(m, pm, mat);
    }

    // Mitsuba's plastic parameters: int_ior and ext_ior (defaults
    // "polypropylene" and "air"), diffuse_reflectance (default 0.5),
    // specular_reflectance (default 1) and nonlinear (default false).
    void read_plastic(const Json& m, const Ptr& pm, Material& mat) {
        mat.int_ior = 1.49;
        if (const auto it = m.find("int_ior"); it != m.end())
            mat.int_ior = ior(*it, pm / "int_ior");
        if (const auto it = m.find("ext_ior"); it != m.end())
            mat.ext_ior = ior(*it, pm / "ext_ior");
        mat.reflectance = glm::dvec3(0.5);
        if (const auto it = m.find("diffuse_reflectance"); it != m.end())
            mat.reflectance = colour(*it, pm / "diffuse_reflectance", mat.reflectance_texture);
        if (const auto it = m.find("specular_reflectance"); it != m.end())
            mat.specular = colour(*it, pm / "specular_reflectance", mat.specular_texture);
        if (const auto it = m.find("nonlinear"); it != m.end()) {
            if (!it->is_boolean())
                fail(pm / "nonlinear", "expected true or false, got " + describe(*it));
            mat.nonlinear = it->get<bool>();
        }
        read_emission(m, pm, mat);
    }

    double ior(const Json& value, const Ptr& p) const {
        if (value.is_string()) {
            const std::string& name = value.get_ref<const std::string&>();
            if (const NamedIor* named = find_ior(name))
                return named->ior;
            std::string known;
            for (const NamedIor& n : named_iors())
                known += (known.empty() ? "" : ", ") + std::string(n.name);
            fail(p, "unknown index of refraction '" + shorten(name, 40) +
                        "' (expected a number or " + known + ")");
        }
        const double v = number(value, p);
        if (!(v > 0.0) || v > scene_limits::max_index)
            fail(p, "must be in (0, 1e4], got " + number_text(v));
        return v;
    }

    // Mitsuba's roughconductor roughness: "distribution" ("beckmann", the
    // default, or "ggx") and "alpha" (default 0.1) or "alpha_u" and "alpha_v"
    // together for an anisotropic surface.
    void read_roughness(const Json& m, const Ptr& pm, Material& mat) {
        if (const auto it = m.find("distribution"); it != m.end()) {
            const std::string& d = expect_string(*it, pm / "distribution");
            if (d == "beckmann")
                mat.distribution = MicrofacetDistribution::Beckmann;
            else if (d == "ggx")
                mat.distribution = MicrofacetDistribution::Ggx;
            else
                fail(pm / "distribution",
                     "unknown distribution '" + shorten(d, 40) + "' (expected beckmann or ggx)");
        }
        const bool u = m.find("alpha_u") != m.end(), v = m.find("alpha_v") != m.end();
        if (m.find("alpha") != m.end()) {
            if (u || v)
                fail(pm / "alpha", "give either alpha or alpha_u and alpha_v, not both");
            mat.alpha_u = mat.alpha_v = roughness(m, pm, "alpha", mat.alpha_u_texture);
            mat.alpha_v_texture = mat.alpha_u_texture;
        } else if (u != v) {
            fail(pm / (u ? "alpha_v" : "alpha_u"), "alpha_u and alpha_v go together");
        } else if (u) {
            mat.alpha_u = roughness(m, pm, "alpha_u", mat.alpha_u_texture);
            mat.alpha_v = roughness(m, pm, "alpha_v", mat.alpha_v_texture);
        }
    }

    // A roughness: a number in (0, 4], or a texture object whose luminance
    // the kernels take (clamped to at least 1e-4), its number k + 1 into
    // `texture`.
    double roughness(const Json& m, const Ptr& pm, const char* key, std::uint32_t& texture) {
        if (m.at(key).is_object()) {
            texture = read_texture(m.at(key), pm / key);
            return 0.1;
        }
        const double a = number(m.at(key), pm / key);
        if (!(a > 0.0) || a > scene_limits::max_alpha)
            fail(pm / key, "must be in (0, 4], got " + number_text(a));
        return a;
    }

    std::uint32_t material_ref(const Json& shape, const Ptr& p) const {
        const Ptr pm = p / "material";
        const std::string& name = expect_string(require(shape, p, "material"), pm);
        const auto it = material_index_.find(name);
        if (it == material_index_.end()) {
            std::string known;
            std::size_t listed = 0;
            for (const Material& m : scene_.materials) {
                if (listed++ == 12) {
                    known += ", ...";
                    break;
                }
                known += (known.empty() ? "" : ", ") + shorten(m.name, 40);
            }
            fail(pm, "unknown material '" + shorten(name, 60) + "' (defined: " + known + ")");
        }
        return it->second;
    }

    // --- shapes ---------------------------------------------------------------

    void add_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      std::uint32_t material, const std::string& where, const char* which,
                      const std::array<glm::dvec2, 3>* uvs = nullptr) {
        if (is_zero_area(a, b, c)) {
            scene_.warnings.push_back(where + ": skipped zero-area triangle" + which);
            return;
        }
        Triangle t{{a, b, c}, material};
        if (uvs) {
            t.has_uvs = true;
            t.uvs = *uvs;
        }
        scene_.triangles.push_back(t);
    }

    // "uvs": one [u, v] per vertex (finite numbers), or none.
    std::vector<glm::dvec2> read_uvs(const Json& s, const Ptr& p, std::size_t vertices) const {
        const auto it = s.find("uvs");
        if (it == s.end())
            return {};
        const Ptr pu = p / "uvs";
        if (!it->is_array() || it->size() != vertices)
            fail(pu, "expected an array of " + std::to_string(vertices) +
                         " texture coordinates [u, v], one per vertex, got " + describe(*it));
        std::vector<glm::dvec2> uvs;
        for (std::size_t i = 0; i < vertices; ++i) {
            const Json& uv = (*it)[i];
            if (!uv.is_array() || uv.size() != 2)
                fail(pu / i, "expected [u, v], got " + describe(uv));
            uvs.emplace_back(number(uv[0], pu / i / 0), number(uv[1], pu / i / 1));
            check_range(uvs.back().x, pu / i / 0, Range::Coordinate);
            check_range(uvs.back().y, pu / i / 1, Range::Coordinate);
        }
        return uvs;
    }

    void read_quad(const Json& quad, const std::vector<glm::dvec3>& v, std::uint32_t material,
                   const Ptr& p) {
        const bool zero1 = is_zero_area(v[0], v[1], v[2]);
        const bool zero2 = is_zero_area(v[0], v[2], v[3]);
        if (!zero1 || !zero2) {
            const glm::dvec3 n1 = glm::cross(v[1] - v[0], v[2] - v[0]);
            const glm::dvec3 n2 = glm::cross(v[2] - v[0], v[3] - v[0]);
            double size = 0.0;
            for (std::size_t i = 0; i < 4; ++i)
                for (std::size_t j = i + 1; j < 4; ++j)
                    size = std::max(size, glm::length(v[j] - v[i]));
            // The plane of the larger half; the remaining corner must lie on it.
            const bool first = glm::length(n1) >= glm::length(n2);
            const glm::dvec3 n = glm::normalize(first ? n1 : n2);
            const std::size_t other = first ? 3 : 1;
            const double off = std::abs(glm::dot(n, v[other] - v[0]));
            if (off > scene_limits::quad_planarity_relative * size)
                fail(p / "vertices", "the 4 corners are not coplanar: corner " +
                                         std::to_string(other) + " is " + fmt4(off) +
                                         " off the plane of the other three (tolerance 1e-6 x "
                                         "quad size " +
                                         fmt4(size) + ")");
            if (!zero1 && !zero2 && glm::dot(n1, n2) < 0.0)
                fail(p / "vertices",
                     "the quad is folded or not convex at corner 1 or 3: its halves (0, 1, 2) and "
                     "(0, 2, 3) face opposite ways; list the corners in order around the quad");
        }
        // Texture coordinates: the file's, or the corners of the unit square
        // in order, as Mitsuba's rectangle has them.
        std::vector<glm::dvec2> uv = read_uvs(quad, p, 4);
        if (uv.empty())
            uv = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};
        const std::array<glm::dvec2, 3> uv1{uv[0], uv[1], uv[2]}, uv2{uv[0], uv[2], uv[3]};
        const std::string where = pointer_text(p);
        add_triangle(v[0], v[1], v[2], material, where, " (corners 0, 1, 2) of the quad", &uv1);
        add_triangle(v[0], v[2], v[3], material, where, " (corners 0, 2, 3) of the quad", &uv2);
    }

    void read_mesh(const Json& s, std::uint32_t material, const Ptr& p) {
        const std::vector<glm::dvec3> verts = points(require(s, p, "vertices"), p / "vertices", 0);
        const std::vector<glm::dvec2> uv = read_uvs(s, p, verts.size());
        const Ptr pt = p / "triangles";
        const Json& tris = require(s, p, "triangles");
        if (!tris.is_array())
            fail(pt, "expected an array of [i, j, k] vertex index triples, got " + describe(tris));
        if (tris.empty())
            fail(pt, "must contain at least one triangle");
        for (std::size_t t = 0; t < tris.size(); ++t) {
            const Ptr pi = pt / t;
            const Json& tri = tris[t];
            if (!tri.is_array() || tri.size() != 3)
                fail(pi, "expected an array of 3 vertex indices, got " + describe(tri));
            std::array<std::size_t, 3> idx{};
            for (std::size_t k = 0; k < 3; ++k) {
                const double x = whole_number(tri[k], pi / k);
                if (x < 0.0 || x >= static_cast<double>(verts.size()))
                    fail(pi / k, "vertex index " + number_text(x) + " out of range: the mesh has " +
                                     std::to_string(verts.size()) + " vertices (0-based)");
                idx[k] = static_cast<std::size_t>(x);
            }
            const std::array<glm::dvec2, 3> uvs =
                uv.empty() ? std::array<glm::dvec2, 3>{}
                           : std::array<glm::dvec2, 3>{uv[idx[0]], uv[idx[1]], uv[idx[2]]};
            add_triangle(verts[idx[0]], verts[idx[1]], verts[idx[2]], material, pointer_text(pi),
                         "", uv.empty() ? nullptr : &uvs);
        }
    }

    NormalSource normal_source(const Json& v, const Ptr& p) const {
        const std::string& name = expect_string(v, p);
        if (name == "file")
            return NormalSource::File;
        if (name == "smooth")
            return NormalSource::Smooth;
        if (name == "none")
            return NormalSource::None;
        fail(p, "unknown normals '" + shorten(name, 40) + "' (expected file, smooth or none)");
    }

    // A mesh shape with a `file`: the file's triangles, placed by `transform`,
    // appended to Scene::triangles (held indexed). Its `usemtl` names that are scene materials
    // give those materials, every other face gets `material`. Vertex normals
    // (from the file, or smooth ones on request) become the triangles' shading
    // normals.
    void read_mesh_file(const Json& s, std::uint32_t material, const Ptr& p) {
        const Ptr pf = p / "file";
        const std::string& file = expect_string(require(s, p, "file"), pf);
        if (file.empty())
            fail(pf, "must name a mesh file (.obj or .ply)");
        MeshLoadOptions options;
        if (const auto it = s.find("normals"); it != s.end())
            options.normals = normal_source(*it, p / "normals");
        if (const auto it = s.find("transform"); it != s.end())
            options.transform = read_transform(*this, *it, p / "transform");
        // Only a scene with textures reads them (materials come before shapes).
        options.texture_coordinates = !scene_.textures.empty();

        TriangleMesh mesh;
        scene_.files.push_back((folder_ / file).string());
        try {
            mesh = load_mesh(folder_ / file, options);
        } catch (const MeshError& e) {
            fail(pf, e.what()); // the mesh's message names the file and the place in it
        }
        std::vector<std::string> warnings = std::move(mesh.warnings);
        std::vector<std::uint32_t> materials =
            resolve_materials(mesh, scene_.materials, material, warnings);
        for (const std::string& w : warnings)
            scene_.warnings.push_back(pointer_text(pf) + ": " + w);

        // load_mesh dropped the zero-area triangles (with one warning counting
        // them), so every triangle is kept, indexed as the file has it.
        IndexedTriangles indexed;
        indexed.positions = std::move(mesh.positions);
        indexed.normals = std::move(mesh.normals);
        indexed.uvs = std::move(mesh.uvs);
        indexed.corners = std::move(mesh.triangles);
        // One material for every face (the common case) is held once.
        if (std::adjacent_find(materials.begin(), materials.end(), std::not_equal_to<>()) ==
            materials.end())
            indexed.material = materials.empty() ? material : materials.front();
        else
            indexed.materials = std::move(materials);
        scene_.triangles.append(std::move(indexed));
    }

    void read_sphere(const Json& s, std::uint32_t material, const Ptr& p) {
        Sphere sp;
        sp.center = vec3(require(s, p, "center"), p / "center", Range::Coordinate);
        const Ptr pr = p / "radius";
        sp.radius = number(require(s, p, "radius"), pr);
        if (sp.radius <= 0.0)
            fail(pr, "must be positive, got " + number_text(sp.radius));
        check_range(sp.radius, pr, Range::Coordinate);
        sp.material = material;
        scene_.spheres.push_back(sp);
    }

    // A mesh is either a file or inline vertices and triangles; the file's
    // options (normals, transform) do not apply to inline meshes.
    void check_mesh_keys(const Json& s, const Ptr& p) const {
        if (s.contains("file")) {
            for (const char* inline_key : {"vertices", "triangles"})
                if (s.contains(inline_key))
                    fail(p / inline_key, "give either 'file' or 'vertices' and 'triangles', "
                                         "not both");
            check_keys(s, p, {"type", "file", "material", "name", "normals", "transform"});
            return;
        }
        for (const char* file_key : {"normals", "transform"})
            if (s.contains(file_key))
                fail(p / file_key, "'" + std::string(file_key) +
                                       "' applies to mesh files only (give 'file'); inline "
                                       "vertices are already in scene coordinates");
        if (!s.contains("vertices") && !s.contains("triangles"))
            fail(p / "file", "missing required field 'file' (or give 'vertices' and 'triangles')");
        check_keys(s, p, {"type", "vertices", "uvs", "triangles", "material", "name"});
    }

    // {"type": "shapegroup", "id": "tree", "shapes": [triangles, quads,
    // meshes]}: Mitsuba's shapegroup, shapes read once into a ShapeGroup
    // that instances place (scene/scene.hpp).
    void read_shape_group(const Json& s, const Ptr& p) {
        check_keys(s, p, {"type", "id", "shapes", "name"});
        if (const auto it = s.find("name"); it != s.end())
            expect_string(*it, p / "name");
        const std::string& id = expect_string(require(s, p, "id"), p / "id");
        if (id.empty())
            fail(p / "id", "must name the shape group (instances refer to it by this id)");
        if (group_numbers_.contains(id))
            fail(p / "id", "a second shape group '" + shorten(id, 40) + "' (ids are unique)");
        const Ptr pg = p / "shapes";
        const Json& shapes = require(s, p, "shapes");
        if (!shapes.is_array() || shapes.empty())
            fail(pg, "expected a non-empty array of shapes (triangle, quad, mesh), got " +
                         describe(shapes));
        // The group's shapes are read as the scene's, into an empty list.
        TriangleList outside = std::move(scene_.triangles);
        scene_.triangles.clear();
        for (std::size_t i = 0; i < shapes.size(); ++i) {
            const Ptr ps = pg / i;
            const Json& shape = shapes[i];
            expect_object(shape, ps, "a shape object");
            const std::string& type = expect_string(require(shape, ps, "type"), ps / "type");
            if (type != "triangle" && type != "quad" && type != "mesh")
                fail(ps / "type", "a shape group holds triangles, quads and meshes, not '" +
                                      shorten(type, 40) +
                                      "' (spheres and nested groups or instances are not "
                                      "supported inside a group)");
            read_shape(shape, ps, type);
        }
        ShapeGroup group;
        group.name = id;
        group.triangles = std::move(scene_.triangles);
        scene_.triangles = std::move(outside);
        if (const std::string problem = group_material_problem(group, scene_.materials);
            !problem.empty())
            fail(p, problem);
        group_numbers_.emplace(id, static_cast<std::uint32_t>(scene_.shape_groups.size()));
        scene_.shape_groups.push_back(std::move(group));
    }

    // {"type": "instance", "shapegroup": "tree", "to_world": [transform
    // steps]}: Mitsuba's instance of a shape group defined before it.
    void read_instance(const Json& s, const Ptr& p) {
        check_keys(s, p, {"type", "shapegroup", "to_world", "name"});
        if (const auto it = s.find("name"); it != s.end())
            expect_string(*it, p / "name");
        const std::string& id = expect_string(require(s, p, "shapegroup"), p / "shapegroup");
        const auto found = group_numbers_.find(id);
        if (found == group_numbers_.end()) {
            std::string known;
            for (const ShapeGroup& g : scene_.shape_groups)
                known += (known.empty() ? "" : ", ") + shorten(g.name, 40);
            fail(p / "shapegroup", "unknown shape group '" + shorten(id, 40) + "' (" +
                                       (known.empty() ? std::string("none is defined")
                                                      : "defined before this instance: " + known) +
                                       ")");
        }
        Instance instance;
        instance.group = found->second;
        if (const auto it = s.find("to_world"); it != s.end())
            instance.to_world = read_transform(*this, *it, p / "to_world").matrix();
        if (const std::string problem = instance_transform_problem(instance.to_world);
            !problem.empty())
            fail(p / "to_world", problem);
        scene_.instances.push_back(instance);
    }

    // One triangle, quad, mesh or sphere shape, its keys checked.
    void read_shape(const Json& s, const Ptr& ps, const std::string& type) {
        if (type == "triangle" || type == "quad") {
            check_keys(s, ps, {"type", "vertices", "uvs", "material", "name"});
        } else if (type == "mesh") {
            check_mesh_keys(s, ps);
        } else if (type == "sphere") {
            check_keys(s, ps, {"type", "center", "radius", "material", "name"});
        } else {
            fail(ps / "type", "unknown shape type '" + shorten(type, 40) +
                                  "' (expected triangle, quad, mesh, sphere, shapegroup or "
                                  "instance)");
        }
        if (const auto it = s.find("name"); it != s.end())
            expect_string(*it, ps / "name");
        const std::uint32_t material = material_ref(s, ps);

        if (type == "triangle") {
            const auto v = points(require(s, ps, "vertices"), ps / "vertices", 3);
            const std::vector<glm::dvec2> uv = read_uvs(s, ps, 3);
            const std::array<glm::dvec2, 3> uvs{uv.empty() ? glm::dvec2(0.0) : uv[0],
                                                uv.empty() ? glm::dvec2(0.0) : uv[1],
                                                uv.empty() ? glm::dvec2(0.0) : uv[2]};
            add_triangle(v[0], v[1], v[2], material, pointer_text(ps), "",
                         uv.empty() ? nullptr : &uvs);
        } else if (type == "quad") {
            read_quad(s, points(require(s, ps, "vertices"), ps / "vertices", 4), material, ps);
        } else if (type == "mesh") {
            if (s.contains("file"))
                read_mesh_file(s, material, ps);
            else
                read_mesh(s, material, ps);
        } else {
            read_sphere(s, material, ps);
        }
    }

    void read_shapes(const Json& shapes, const Ptr& p) {
        if (!shapes.is_array())
            fail(p, "expected an array of shapes, got " + describe(shapes));
        if (shapes.empty())
            fail(p, "the scene has no shapes");
        for (std::size_t i = 0; i < shapes.size(); ++i) {
            const Ptr ps = p / i;
            const Json& s = shapes[i];
            expect_object(s, ps, "a shape object");
            const std::string& type = expect_string(require(s, ps, "type"), ps / "type");
            if (type == "shapegroup")
                read_shape_group(s, ps);
            else if (type == "instance")
                read_instance(s, ps);
            else
                read_shape(s, ps, type);
        }
        if (scene_.triangles.empty() && scene_.spheres.empty() && scene_.instances.empty())
            fail(p, "every shape was skipped (all triangles have zero area): nothing to render");
    }

    // --- emitters -------------------------------------------------------------

    // "emitters": lights that are not surfaces, named and parameterised as
    // Mitsuba 3's plugins (docs/scene-format.md#emitters): point (position,
    // intensity), spot (position, direction, intensity, cutoff_angle,
    // beam_width), directional (direction, irradiance), constant (radiance),
    // envmap (filename, scale, to_world).
    void read_emitters(const Json& list, const Ptr& p) {
        if (!list.is_array())
            fail(p, "expected an array of emitters, got " + describe(list));
        for (std::size_t i = 0; i < list.size(); ++i) {
            const Ptr pe = p / i;
            const Json& e = list[i];
            expect_object(e, pe, "an emitter object");
            const std::string& type = expect_string(require(e, pe, "type"), pe / "type");
            Emitter out;
            if (type == "point") {
                check_keys(e, pe, {"type", "position", "intensity"});
                out.kind = EmitterKind::Point;
                out.position = vec3(require(e, pe, "position"), pe / "position", Range::Coordinate);
                out.value = vec3(require(e, pe, "intensity"), pe / "intensity", Range::Radiance);
            } else if (type == "spot") {
                check_keys(
                    e, pe,
                    {"type", "position", "direction", "intensity", "cutoff_angle", "beam_width"});
                out.kind = EmitterKind::Spot;
                out.position = vec3(require(e, pe, "position"), pe / "position", Range::Coordinate);
                out.direction = unit_direction(e, pe);
                out.value = vec3(require(e, pe, "intensity"), pe / "intensity", Range::Radiance);
                read_spot_angles(e, pe, out);
            } else if (type == "directional") {
                check_keys(e, pe, {"type", "direction", "irradiance"});
                out.kind = EmitterKind::Directional;
                out.direction = unit_direction(e, pe);
                out.value = vec3(require(e, pe, "irradiance"), pe / "irradiance", Range::Radiance);
            } else if (type == "constant") {
                check_keys(e, pe, {"type", "radiance"});
                out.kind = EmitterKind::Constant;
                out.value = vec3(require(e, pe, "radiance"), pe / "radiance", Range::Radiance);
            } else if (type == "envmap") {
                read_envmap(e, pe, out);
            } else {
                fail(pe / "type", "unknown emitter type '" + shorten(type, 40) +
                                      "' (expected point, spot, directional, constant or envmap)");
            }
            if (out.kind == EmitterKind::Constant || out.kind == EmitterKind::Envmap)
                if (find_environment(scene_.emitters))
                    fail(pe, "a second environment (constant or envmap emitter): a scene has at "
                             "most one");
            scene_.emitters.push_back(out);
        }
    }

    // An envmap: {"type": "envmap", "filename": "sky.exr", "scale": 1,
    // "to_world": [transform steps]}, Mitsuba's parameters (an image file
    // as a bitmap texture reads it, sRGB files made linear; scale >= 0; a
    // to_world that only rotates).
    void read_envmap(const Json& e, const Ptr& pe, Emitter& out) {
        check_keys(e, pe, {"type", "filename", "scale", "to_world"});
        out.kind = EmitterKind::Envmap;
        if (const auto it = e.find("scale"); it != e.end()) {
            const double scale = number(*it, pe / "scale");
            if (!(scale >= 0.0 && scale <= scene_limits::max_radiance))
                fail(pe / "scale", "must be in [0, " + number_text(scene_limits::max_radiance) +
                                       "], got " + number_text(scale));
            out.value = glm::dvec3(scale);
        }
        if (const auto it = e.find("to_world"); it != e.end()) {
            const Transform to_world = read_transform(*this, *it, pe / "to_world");
            out.to_world = glm::dmat3(to_world.matrix());
            if (!is_rotation(out.to_world))
                fail(pe / "to_world", "must be a rotation (an environment map is only turned: no "
                                      "scale, shear or mirror)");
        }
        const Ptr pf = pe / "filename";
        out.filename = expect_string(require(e, pe, "filename"), pf);
        const std::filesystem::path path = folder_ / out.filename;
        out.path = path.string();
        scene_.files.push_back(out.path);
        out.image = load_texture_image(path, false, pf);
    }

    // An emitter's "direction": any length but zero, made unit.
    glm::dvec3 unit_direction(const Json& e, const Ptr& pe) const {
        const glm::dvec3 d = vec3(require(e, pe, "direction"), pe / "direction", Range::Coordinate);
        const double length = glm::length(d);
        if (!(length > 0.0) || !std::isfinite(length))
            fail(pe / "direction", "must be a non-zero vector of finite length");
        return d / length;
    }

    // A spot's angles in degrees: cutoff_angle in (0, 180] (0 would light
    // nothing: Mitsuba renders it black; here it is an error), beam_width in
    // [0, 180], by default 3/4 of the cutoff, as in Mitsuba.
    void read_spot_angles(const Json& e, const Ptr& pe, Emitter& out) const {
        if (const auto it = e.find("cutoff_angle"); it != e.end()) {
            out.cutoff_angle = number(*it, pe / "cutoff_angle");
            if (!(out.cutoff_angle > 0.0 && out.cutoff_angle <= 180.0))
                fail(pe / "cutoff_angle",
                     "must be in (0, 180] degrees (a zero cutoff lights nothing), got " +
                         number_text(out.cutoff_angle));
        }
        out.beam_width = 0.75 * out.cutoff_angle;
        if (const auto it = e.find("beam_width"); it != e.end()) {
            out.beam_width = number(*it, pe / "beam_width");
            if (!(out.beam_width >= 0.0 && out.beam_width <= 180.0))
                fail(pe / "beam_width",
                     "must be in [0, 180] degrees, got " + number_text(out.beam_width));
        }
    }

    std::filesystem::path folder_;
    Scene scene_;
    std::map<std::string, std::uint32_t> group_numbers_; // shape group id -> Scene::shape_groups
    std::unordered_map<std::string, std::uint32_t> material_index_;
    std::map<std::pair<std::string, bool>, std::shared_ptr<const TextureImage>> texture_images_;
};

} // namespace

Scene parse_scene(std::string_view json_text, const std::string& source_name) {
    // Mesh files are relative to the scene file's folder (the working
    // directory for a bare name such as "test.json").
    const std::filesystem::path folder = std::filesystem::path(source_name).parent_path();
    Scene scene = SceneReader(source_name, folder).read(json::parse(json_text, source_name));
    validate_scene(scene); // a backstop: the reader has already checked all of this
    return scene;
}

Scene load_scene(const std::filesystem::path& path) {
    return load_scene(path, SceneReadOptions{});
}

Scene load_scene(const std::filesystem::path& path,
                 const std::map<std::string, std::string>& defines) {
    return load_scene(path, SceneReadOptions{defines});
}

Scene load_scene(const std::filesystem::path& path, const SceneReadOptions& options) {
    if (lower_extension(path) == ".xml")
        return load_mitsuba_scene(path, options);
    const auto& defines = options.defines;
    if (!defines.empty())
        throw SceneError(one_line("-D " + defines.begin()->first + "=...: '" + path.string() +
                                  "' is a JSON scene, which has no $names to set (-D is for "
                                  "Mitsuba XML scenes)"));
    if (options.lenient)
        throw SceneError(one_line("--lenient: '" + path.string() +
                                  "' is a JSON scene, which wavepath reads strictly (--lenient "
                                  "is for Mitsuba XML scenes)"));
    const std::string name = path.string();
    std::string text;
    try {
        text = read_file_text(path);
    } catch (const FileError& e) {
        throw SceneError(one_line("cannot open scene '" + name + "': " + e.reason()));
    }
    return parse_scene(text, name);
}

} // namespace wp
