// A Mitsuba 3 scene put together from its plugins (load_mitsuba.hpp).
#include "scene/mitsuba/load_mitsuba.hpp"

#include <cmath>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "image/image.hpp"
#include "image/texture_image.hpp"
#include "scene/instancing.hpp"
#include "scene/json_reader.hpp"
#include "scene/mitsuba/bsdfs.hpp"
#include "scene/mitsuba/parameters.hpp"
#include "scene/mitsuba/sensor.hpp"
#include "scene/mitsuba/shapes.hpp"
#include "scene/mitsuba/xml_reader.hpp"
#include "scene/validate.hpp"
#include "util/file.hpp"

namespace wp {
namespace mitsuba {
namespace {

using json::number_text;

// An `area` emitter's radiance.
glm::dvec3 read_emitter(const Object& emitter) {
    Parameters p(emitter);
    if (emitter.type != "area")
        p.fail("unsupported emitter inside a shape (wavepath has area emitters)");
    const std::optional<glm::dvec3> radiance = p.color("radiance", SpectrumUse::Emission);
    if (!radiance)
        p.fail("an area emitter needs its radiance");
    check_range(p, "radiance", *radiance, 0.0, scene_limits::max_radiance);
    for (const auto& child : emitter.children)
        fail_at(child->where, child->element(),
                child->tag == "texture" ? "textured radiance is not supported yet (give an <rgb>)"
                                        : "wavepath does not support a <" + child->tag +
                                              "> inside " + emitter.element());
    p.finish();
    return *radiance;
}

// An envmap's parameters (Mitsuba 3.9.1's): filename, scale, to_world (a
// rotation here), mis_compensation (how Mitsuba samples it: no change to the
// image, read and dropped).
void read_envmap(Parameters& p, const Object& emitter, const std::optional<wp::Transform>& to_world,
                 Emitter& e) {
    e.kind = EmitterKind::Envmap;
    const std::optional<std::string> filename = p.string("filename");
    if (!filename)
        p.fail("an envmap needs its filename");
    const double scale = p.number("scale").value_or(1.0);
    if (!(scale >= 0.0 && scale <= scene_limits::max_radiance))
        p.fail("scale", "must be in [0, " + number_text(scene_limits::max_radiance) + "], got " +
                            number_text(scale));
    e.value = glm::dvec3(scale);
    if (to_world) {
        e.to_world = glm::dmat3(to_world->matrix());
        if (!is_rotation(e.to_world))
            p.fail("to_world", "must be a rotation (wavepath turns an environment map, but does "
                               "not scale, shear or mirror it)");
    }
    p.ignore("mis_compensation");
    e.filename = *filename;
    const std::filesystem::path path = emitter.resolve(*filename);
    e.path = path.string();
    try {
        e.image = std::make_shared<const TextureImage>(read_texture_image(path, false));
    } catch (const FileError& error) {
        p.fail("filename", error.what());
    } catch (const ImageError& error) {
        p.fail("filename", error.what());
    }
}

// An emitter at the scene's top level: point, spot, directional, constant,
// with Mitsuba 3.9.1's parameters and defaults (docs/mitsuba-import.md).
Emitter read_scene_emitter(const Object& emitter) {
    Parameters p(emitter);
    Emitter e;
    auto value = [&](const char* name) {
        const glm::dvec3 v =
            p.color(name, SpectrumUse::Emission).value_or(glm::dvec3(1.0)); // Mitsuba's default
        check_range(p, name, v, 0.0, scene_limits::max_radiance);
        return v;
    };
    // Where a point or spot is and which way a spot or sun points: its
    // to_world's origin and z axis, as Mitsuba places them.
    const std::optional<wp::Transform> to_world = p.transform("to_world");
    auto unit_axis = [&](const glm::dvec3& axis, const char* name) {
        const double length = glm::length(axis);
        if (!(length > 0.0) || !std::isfinite(length))
            p.fail(name, "gives no direction (a zero or non-finite vector)");
        return axis / length;
    };
    if (emitter.type == "point") {
        e.kind = EmitterKind::Point;
        e.value = value("intensity");
        const std::optional<glm::dvec3> position = p.point("position");
        if (position && to_world)
            p.fail("position", "give either position or to_world, not both (as Mitsuba)");
        e.position = position ? *position
                              : to_world.value_or(wp::Transform()).apply_to_point(glm::dvec3(0.0));
    } else if (emitter.type == "spot") {
        e.kind = EmitterKind::Spot;
        e.value = value("intensity");
        const wp::Transform t = to_world.value_or(wp::Transform());
        e.position = t.apply_to_point(glm::dvec3(0.0));
        e.direction = unit_axis(t.apply_to_vector({0.0, 0.0, 1.0}), "to_world");
        e.cutoff_angle = p.number("cutoff_angle").value_or(20.0);
        if (!(e.cutoff_angle > 0.0 && e.cutoff_angle <= 180.0))
            p.fail("cutoff_angle", "must be in (0, 180] degrees (a zero cutoff lights nothing), "
                                   "got " +
                                       number_text(e.cutoff_angle));
        e.beam_width = p.number("beam_width").value_or(0.75 * e.cutoff_angle);
        if (!(e.beam_width >= 0.0 && e.beam_width <= 180.0))
            p.fail("beam_width", "must be in [0, 180] degrees, got " + number_text(e.beam_width));
    } else if (emitter.type == "directional") {
        e.kind = EmitterKind::Directional;
        e.value = value("irradiance");
        const std::optional<glm::dvec3> direction = p.point("direction");
        if (direction && to_world)
            p.fail("direction", "give either direction or to_world, not both (as Mitsuba)");
        e.direction =
            direction
                ? unit_axis(*direction, "direction")
                : unit_axis(to_world.value_or(wp::Transform()).apply_to_vector({0.0, 0.0, 1.0}),
                            "to_world");
    } else if (emitter.type == "constant") {
        e.kind = EmitterKind::Constant;
        // A to_world (taken above) turns a uniform sky into itself: Mitsuba
        // accepts it, and so does wavepath, changing nothing.
        e.value = value("radiance");
    } else if (emitter.type == "envmap") {
        read_envmap(p, emitter, to_world, e);
    } else {
        p.fail("unsupported emitter at the scene's top level (wavepath reads point, spot, "
               "directional, constant and envmap; area emitters go inside shapes)");
    }
    for (const auto& child : emitter.children)
        fail_at(child->where, child->element(),
                child->tag == "texture" ? "textured emitters are not supported (give an <rgb>)"
                                        : "wavepath does not support a <" + child->tag +
                                              "> inside " + emitter.element());
    p.finish();
    return e;
}

// The top-level emitters read_scene_emitter reads (--lenient leaves the
// others out).
bool is_supported_scene_emitter(const std::string& type) {
    return type == "point" || type == "spot" || type == "directional" || type == "constant" ||
           type == "envmap";
}

// Mitsuba's `path` integrator: max_depth and rr_depth as Mitsuba reads
// them, applied by the renderer (Scene::max_depth; docs/mitsuba-import.md,
// "max_depth"). Mitsuba takes a max_depth of 0 and renders black; wavepath
// refuses it with the other values that render nothing.
void read_integrator(const Object& integrator, Scene& scene) {
    Parameters p(integrator);
    if (integrator.type != "path")
        p.fail("unsupported integrator '" + json::shorten(integrator.type, 40) +
               "' (wavepath renders with Mitsuba's path integrator; --lenient renders the scene "
               "with it)");
    constexpr long long kMostDepth = 1 << 20; // the command line's --max-depth bound
    const long long max_depth = p.integer("max_depth").value_or(-1);
    if (max_depth != -1 && !(max_depth >= 1 && max_depth <= kMostDepth))
        p.fail("max_depth", "must be -1 (no limit) or in [1, " + std::to_string(kMostDepth) +
                                "] (the longest path in edges, the camera ray included), got " +
                                std::to_string(max_depth));
    const std::optional<long long> rr_depth = p.integer("rr_depth");
    if (rr_depth && !(*rr_depth >= 1 && *rr_depth <= kMostDepth))
        p.fail("rr_depth", "must be in [1, " + std::to_string(kMostDepth) + "], got " +
                               std::to_string(*rr_depth));
    scene.max_depth = static_cast<int>(max_depth);
    scene.rr_depth = static_cast<std::uint32_t>(rr_depth.value_or(0));
    scene.hide_emitters = p.boolean("hide_emitters").value_or(false);
    for (const auto& child : integrator.children)
        fail_at(child->where, child->element(),
                "wavepath does not support a <" + child->tag + "> inside " + integrator.element());
    p.finish();
}

class SceneAssembler {
  public:
    explicit SceneAssembler(bool lenient) : lenient_(lenient) {}

    Scene assemble(const std::filesystem::path& path,
                   const std::map<std::string, std::string>& defines) {
        const Document document = read_document(path, defines);
        scene_.source = path.string();
        scene_.mitsuba_depths = true; // --max-depth counts edges, as max_depth does
        scene_.files.assign(document.files.begin() + 1, document.files.end());
        const Object& root = *document.scene;
        bool has_sensor = false;
        for (const auto& child : root.children) {
            const Object& object = *child;
            if (object.tag == "sensor") {
                if (has_sensor) {
                    scene_.warnings.push_back(object.where.text() + ": " + object.element() +
                                              ": a second sensor; wavepath renders the first");
                    continue;
                }
                scene_.camera = read_sensor(object, scene_.warnings);
                has_sensor = true;
            } else if (object.tag == "shape" && object.type == "shapegroup") {
                (void)shape_group(object); // instances may refer to it
            } else if (object.tag == "shape" && object.type == "instance") {
                add_instance(object);
            } else if (object.tag == "shape") {
                if (lenient_ && !is_supported_shape(object.type)) {
                    left_out(object, "left out: wavepath has no '" +
                                         json::shorten(object.type, 40) + "' shape");
                    continue;
                }
                add_shape_with_material(object);
            } else if (object.tag == "integrator") {
                if (lenient_ && object.type != "path") {
                    left_out(object, "left out: wavepath renders with its path tracer (Mitsuba's "
                                     "path) and that integrator's defaults");
                    continue;
                }
                read_integrator(object, scene_);
            } else if ((object.tag == "bsdf" || object.tag == "texture" ||
                        (object.tag == "emitter" && object.type == "area")) &&
                       !object.id.empty()) {
                // Declared for <ref>s; read where a shape uses it (an area
                // emitter too: mitsuba-data's cbox-rgb.xml declares its
                // light's at the top level, and the luminaire refers to it).
            } else if (object.tag == "emitter") {
                if (lenient_ && !is_supported_scene_emitter(object.type)) {
                    left_out(object, "left out: wavepath has no '" +
                                         json::shorten(object.type, 40) + "' emitter");
                    continue;
                }
                const Emitter e = read_scene_emitter(object);
                if ((e.kind == EmitterKind::Constant || e.kind == EmitterKind::Envmap) &&
                    find_environment(scene_.emitters))
                    fail_at(object.where, object.element(),
                            "a second environment (constant or envmap emitter): wavepath's "
                            "scene has at most one");
                if (e.kind == EmitterKind::Envmap)
                    scene_.files.push_back(e.path);
                scene_.emitters.push_back(e);
            } else {
                fail_at(object.where, object.element(),
                        "unsupported at the scene's top level (wavepath reads sensor, "
                        "integrator, shape, and bsdf with an id)");
            }
        }
        scene_.textures = textures_.take();
        for (const Texture& t : scene_.textures)
            if (t.kind == TextureKind::Bitmap)
                scene_.files.push_back(t.path);
        if (!root.parameters.empty())
            fail_at(root.parameters.front().where, root.parameters.front().element,
                    "a value outside any plugin");
        if (!has_sensor)
            fail_at(root.where, "<scene>",
                    "the scene has no <sensor> (wavepath needs a "
                    "perspective or thinlens camera)");
        if (scene_.triangles.empty() && scene_.spheres.empty() && scene_.instances.empty())
            fail_at(root.where, "<scene>", "the scene has no shapes");
        validate_scene(scene_); // a backstop: the readers have checked all of this
        return std::move(scene_);
    }

  private:
    // Mitsuba's shapegroup: its shapes read once, in object space, into a
    // ShapeGroup (scene/scene.hpp). Triangle shapes only: a sphere, an area
    // emitter (Mitsuba refuses those in a group too) or a nested group is
    // refused with the group named. Returns the group's index; a group that
    // an instance read first is not read again.
    std::uint32_t shape_group(const Object& group) {
        if (const auto it = groups_.find(&group); it != groups_.end())
            return it->second;
        Parameters p(group);
        p.finish();
        const std::string name = group.id.empty() ? "at " + group.where.text() : group.id;
        TriangleList outside = std::move(scene_.triangles);
        scene_.triangles.clear();
        const std::size_t spheres = scene_.spheres.size();
        for (const auto& child : group.children) {
            const Object& shape = *child;
            if (shape.tag != "shape" || shape.type == "shapegroup" || shape.type == "instance")
                fail_at(shape.where, shape.element(),
                        "not supported inside shapegroup '" + name +
                            "' (it holds triangle shapes: obj, ply, serialized, rectangle, cube, "
                            "disk)");
            for (const auto& grandchild : shape.children)
                if (grandchild->tag == "emitter")
                    fail_at(grandchild->where, grandchild->element(),
                            "an emitter inside shapegroup '" + name +
                                "': emitters cannot be instanced (as in Mitsuba); place the "
                                "emitting shape outside the group");
            if (lenient_ && !is_supported_shape(shape.type)) {
                left_out(shape,
                         "left out: wavepath has no '" + json::shorten(shape.type, 40) + "' shape");
                continue;
            }
            if (shape.type == "sphere")
                fail_at(shape.where, shape.element(),
                        "a sphere inside shapegroup '" + name +
                            "' is not supported (instances hold triangles: use a sphere mesh, "
                            "or place the sphere outside the group)");
            add_shape_with_material(shape);
        }
        if (scene_.spheres.size() != spheres)
            fail_at(group.where, group.element(), "a sphere inside a shapegroup");
        ShapeGroup out;
        out.name = name;
        out.triangles = std::move(scene_.triangles);
        scene_.triangles = std::move(outside);
        if (out.triangles.empty())
            fail_at(group.where, group.element(), "an empty shapegroup");
        const auto index = static_cast<std::uint32_t>(scene_.shape_groups.size());
        scene_.shape_groups.push_back(std::move(out));
        groups_.emplace(&group, index);
        return index;
    }

    // Mitsuba's instance: one <ref> to a shapegroup, placed by to_world.
    void add_instance(const Object& instance) {
        Parameters p(instance);
        const Object* group = nullptr;
        for (const auto& child : instance.children) {
            if (child->tag != "shape" || child->type != "shapegroup" || group)
                fail_at(child->where, child->element(),
                        "an instance takes exactly one shapegroup (a <ref> to its id)");
            group = child.get();
        }
        if (!group)
            p.fail("an instance without its shapegroup (give <ref id=\"...\"/>)");
        Instance out;
        out.group = shape_group(*group);
        out.to_world = p.transform("to_world").value_or(wp::Transform()).matrix();
        if (const std::string problem = instance_transform_problem(out.to_world); !problem.empty())
            p.fail("to_world", problem);
        p.finish();
        scene_.instances.push_back(out);
    }

    void add_shape_with_material(const Object& shape) {
        const Object* bsdf = nullptr;
        const Object* emitter = nullptr;
        for (const auto& child : shape.children) {
            const Object*& slot = child->tag == "bsdf" ? bsdf : emitter;
            if (child->tag != "bsdf" && child->tag != "emitter")
                continue; // add_shape refuses it
            if (slot)
                fail_at(child->where, child->element(),
                        "a second <" + child->tag + "> in " + shape.element());
            slot = child.get();
        }
        const glm::dvec3 emission = emitter ? read_emitter(*emitter) : glm::dvec3(0.0);
        const std::uint32_t material = material_of(bsdf, emission);
        add_shape(shape, material, scene_);
    }

    // The material of a BSDF (null: Mitsuba's default, a diffuse 0.5) with
    // an emission: each pair once, in order of first use. A black diffuse
    // that emits is wavepath's emitter kind.
    std::uint32_t material_of(const Object* bsdf, const glm::dvec3& emission) {
        const auto key = std::make_tuple(bsdf, emission.x, emission.y, emission.z);
        if (const auto it = materials_.find(key); it != materials_.end())
            return it->second;
        auto cached = bsdfs_.find(bsdf);
        if (cached == bsdfs_.end()) {
            Material m;
            if (bsdf) {
                m = lenient_ ? read_bsdf_or_grey(*bsdf)
                             : read_bsdf(*bsdf, textures_, scene_.warnings);
                m.name = bsdf->id.empty() ? "bsdf at " + bsdf->where.text() : bsdf->id;
            } else {
                m.kind = MaterialKind::Diffuse;
                m.reflectance = glm::dvec3(0.5);
                m.name = "default diffuse";
            }
            cached = bsdfs_.emplace(bsdf, m).first;
        }
        Material m = cached->second;
        // Mitsuba's default BSDF is a diffuse 0.5, but black on a shape that
        // emits (measured with 3.9.1: a light with no BSDF and one with a
        // black diffuse give the same image, mean 0.371466 in both).
        if (!bsdf && emission != glm::dvec3(0.0))
            m.reflectance = glm::dvec3(0.0);
        if (emission != glm::dvec3(0.0)) {
            m.name += " emitting " + number_text(emission.x) + " " + number_text(emission.y) + " " +
                      number_text(emission.z);
            if (m.kind == MaterialKind::Diffuse && m.reflectance == glm::dvec3(0.0) &&
                !m.is_textured())
                m.kind = MaterialKind::Emitter;
            m.emission = emission;
        }
        const auto index = static_cast<std::uint32_t>(scene_.materials.size());
        scene_.materials.push_back(std::move(m));
        materials_.emplace(key, index);
        return index;
    }

    // --lenient: a BSDF wavepath cannot read, for whatever reason, becomes
    // Mitsuba's default BSDF, a diffuse 0.5, with a warning that says why;
    // the textures it added before it failed are dropped with it.
    Material read_bsdf_or_grey(const Object& bsdf) {
        const TextureTable textures_before = textures_;
        const std::size_t warnings_before = scene_.warnings.size();
        try {
            return read_bsdf(bsdf, textures_, scene_.warnings);
        } catch (const SceneError& error) {
            textures_ = textures_before;
            scene_.warnings.resize(warnings_before);
            // The refusal without its place when it is this element's own.
            std::string reason = error.what();
            const std::string own = bsdf.where.text() + ": " + bsdf.element() + ": ";
            if (reason.rfind(own, 0) == 0)
                reason.erase(0, own.size());
            scene_.warnings.push_back(bsdf.where.text() + ": " + bsdf.element() +
                                      ": replaced by a grey diffuse (reflectance 0.5), as "
                                      "--lenient asks: " +
                                      reason);
            Material grey;
            grey.kind = MaterialKind::Diffuse;
            grey.reflectance = glm::dvec3(0.5);
            return grey;
        }
    }

    // --lenient: an element of a plugin wavepath does not have, left out.
    void left_out(const Object& object, const std::string& what) {
        scene_.warnings.push_back(object.where.text() + ": " + object.element() + ": " + what +
                                  " (--lenient)");
    }

    bool lenient_;
    Scene scene_;
    TextureTable textures_;
    std::map<const Object*, Material> bsdfs_;
    std::map<std::tuple<const Object*, double, double, double>, std::uint32_t> materials_;
    std::map<const Object*, std::uint32_t> groups_; // shapegroup -> Scene::shape_groups
};

} // namespace
} // namespace mitsuba

Scene load_mitsuba_scene(const std::filesystem::path& path, const SceneReadOptions& options) {
    return mitsuba::SceneAssembler(options.lenient).assemble(path, options.defines);
}

} // namespace wp
