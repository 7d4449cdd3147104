// Mitsuba 3's texture plugins as wavepath textures (textures.hpp).
#include "scene/mitsuba/textures.hpp"

#include "image/image.hpp"
#include "scene/json_reader.hpp"
#include "scene/mitsuba/parameters.hpp"
#include "scene/validate.hpp"
#include "util/file.hpp"

namespace wp::mitsuba {

std::uint32_t TextureTable::add(const Object& object) {
    if (const auto it = numbers_.find(&object); it != numbers_.end())
        return it->second;
    Parameters p(object);
    Texture t;
    if (const std::optional<TextureKind> kind = texture_kind_from_name(object.type))
        t.kind = *kind;
    else
        p.fail("unsupported texture type '" + json::shorten(object.type, 40) +
               "' (wavepath reads " + texture_kind_names() + ")");
    if (t.kind == TextureKind::Bitmap) {
        const std::optional<std::string> filename = p.string("filename");
        if (!filename || filename->empty())
            p.fail("a bitmap texture needs a filename");
        t.filename = *filename;
        t.raw = p.boolean("raw").value_or(false);
        if (const std::optional<std::string> name = p.string("filter_type")) {
            const std::optional<TextureFilter> filter = texture_filter_from_name(*name);
            if (!filter)
                p.fail("filter_type", "unknown filter_type '" + json::shorten(*name, 40) +
                                          "' (expected bilinear or nearest)");
            t.filter = *filter;
        }
        if (const std::optional<std::string> name = p.string("wrap_mode")) {
            const std::optional<TextureWrap> wrap = texture_wrap_from_name(*name);
            if (!wrap)
                p.fail("wrap_mode", "unknown wrap_mode '" + json::shorten(*name, 40) +
                                        "' (expected repeat, mirror or clamp)");
            t.wrap = *wrap;
        }
        // How Mitsuba stores the texels on its device, and whether it builds
        // an acceleration for them: no change to the values.
        p.ignore("format");
        p.ignore("accel");
        const std::filesystem::path path = object.resolve(t.filename);
        t.path = path.string();
        const auto key = std::make_pair(path.lexically_normal().string(), t.raw);
        if (const auto it = images_.find(key); it != images_.end()) {
            t.image = it->second;
        } else {
            try {
                t.image = std::make_shared<const TextureImage>(read_texture_image(path, t.raw));
            } catch (const FileError& e) {
                p.fail("filename", e.what());
            } catch (const ImageError& e) {
                p.fail("filename", e.what());
            }
            images_.emplace(key, t.image);
        }
    } else {
        for (const auto& [name, colour] :
             {std::pair{"color0", &t.color0}, std::pair{"color1", &t.color1}})
            if (const std::optional<glm::dvec3> c = p.color(name)) {
                check_range(p, name, *c, 0.0, scene_limits::max_radiance);
                *colour = *c;
            }
    }
    if (const std::optional<wp::Transform> to_uv = p.transform("to_uv")) {
        // Mitsuba applies to_uv to (u, v) as the 3x3 of the 4x4 without its
        // z row and column (measured: a scale then a translate).
        const glm::dmat4& m = to_uv->matrix();
        t.to_u = {m[0][0], m[1][0], m[3][0]};
        t.to_v = {m[0][1], m[1][1], m[3][1]};
    }
    for (const auto& child : object.children)
        fail_at(child->where, child->element(),
                "wavepath does not support a <" + child->tag + "> inside " + object.element());
    p.finish();
    textures_.push_back(std::move(t));
    const auto number = static_cast<std::uint32_t>(textures_.size());
    numbers_.emplace(&object, number);
    return number;
}

} // namespace wp::mitsuba
