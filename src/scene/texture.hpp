// Textures as the scene describes them: Mitsuba 3's `bitmap` and
// `checkerboard` plugins, with their parameters and defaults. A material's
// colour or roughness parameter may name one (Material::*_texture); the
// kernels evaluate it at the hit point's texture coordinates
// (kernels/textures/texture.h). docs/materials.md, "Textures", has the user's
// view.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "image/texture_image.hpp"
#include "wp_shared.h"

namespace wp {

// The texture kinds: the rows of WP_TEXTURES (kernels/wp_shared.h), with the
// kernels' values.
#define WP_TEXTURE_KIND_ENUMERATOR(KIND, Name, name, value) Name = value,
enum class TextureKind : std::uint32_t { WP_TEXTURES(WP_TEXTURE_KIND_ENUMERATOR) };
#undef WP_TEXTURE_KIND_ENUMERATOR

const char* texture_kind_name(TextureKind kind);
std::optional<TextureKind> texture_kind_from_name(std::string_view name);
std::string texture_kind_names(); // "bitmap, checkerboard"

// Mitsuba's wrap_mode and filter_type, with the kernels' values.
enum class TextureWrap : std::uint32_t {
    Repeat = WP_TEXTURE_WRAP_REPEAT,
    Mirror = WP_TEXTURE_WRAP_MIRROR,
    Clamp = WP_TEXTURE_WRAP_CLAMP,
};
enum class TextureFilter : std::uint32_t {
    Bilinear = WP_TEXTURE_FILTER_BILINEAR,
    Nearest = WP_TEXTURE_FILTER_NEAREST,
};
std::optional<TextureWrap> texture_wrap_from_name(std::string_view name);
std::optional<TextureFilter> texture_filter_from_name(std::string_view name);
const char* texture_wrap_name(TextureWrap wrap);
const char* texture_filter_name(TextureFilter filter);

struct Texture {
    TextureKind kind = TextureKind::Checkerboard;
    // The affine map of texture coordinates, Mitsuba's to_uv: (u, v) ->
    // (to_u . (u, v, 1), to_v . (u, v, 1)).
    glm::dvec3 to_u{1.0, 0.0, 0.0};
    glm::dvec3 to_v{0.0, 1.0, 0.0};
    // checkerboard: the two colours (Mitsuba's defaults), linear RGB >= 0.
    glm::dvec3 color0{0.4};
    glm::dvec3 color1{0.2};
    // bitmap: the file as the scene names it and as it was opened, Mitsuba's
    // `raw` (8-bit texels taken as linear, not sRGB), its filter and wrap
    // mode, and the decoded texels (shared: a scene is copied, its texels
    // are not).
    std::string filename;
    std::string path;
    bool raw = false;
    TextureFilter filter = TextureFilter::Bilinear;
    TextureWrap wrap = TextureWrap::Repeat;
    std::shared_ptr<const TextureImage> image;

    // The texture's average over its unit square of texture coordinates,
    // which plastic's sampling weight takes where its diffuse_reflectance is
    // textured (as Mitsuba takes the texture's mean).
    glm::dvec3 mean() const;
    // The value at (u, v) in double precision, by the kernels' rules: the
    // host reference of kernels/textures/ (tests/kernels/test_textures.cpp).
    glm::dvec3 eval(double u, double v) const;
    // The value as a float parameter (a roughness): the luminance of the
    // colour, with a checkerboard's colours swapped, as Mitsuba 3.9.1's
    // eval_1 has them (kernels/textures/checkerboard.h).
    double eval_float(double u, double v) const;
};

} // namespace wp
