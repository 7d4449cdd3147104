#include "image/texture_image.hpp"

#include "image/exr.hpp"
#include "image/image.hpp"
#include "util/file.hpp"

#include <stb_image.h>

#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <memory>
#include <string>

namespace wp {
namespace {

// stb_image hands out malloc'd pixels.
struct StbPixels {
    void* data = nullptr;
    ~StbPixels() { stbi_image_free(data); }
};

void check_size(int width, int height, const std::string& context) {
    if (width <= 0 || height <= 0)
        throw ImageError(context + ": the image is empty");
    if (static_cast<std::uint32_t>(width) > kMaxTextureSide ||
        static_cast<std::uint32_t>(height) > kMaxTextureSide)
        throw ImageError(context + ": the image is " + std::to_string(width) + "x" +
                         std::to_string(height) + " texels; a texture may be at most " +
                         std::to_string(kMaxTextureSide) + " on each side");
}

// Linear float texels, three per texel, into the Float32 packing; each must
// be a finite radiance-like value (a texture is a colour or a roughness).
void pack_floats(const float* rgb, std::size_t texels, TextureImage& out,
                 const std::string& context) {
    out.encoding = TexelEncoding::Float32;
    out.texels.resize(texels * 3);
    for (std::size_t i = 0; i < texels * 3; ++i) {
        const float x = rgb[i];
        if (!std::isfinite(x) || x < 0.0f)
            throw ImageError(context + ": texel " + std::to_string(i / 3) + " is " +
                             (std::isfinite(x) ? "negative" : "not finite") +
                             " (a texture holds colours >= 0)");
        out.texels[i] = std::bit_cast<std::uint32_t>(x);
    }
}

} // namespace

TextureImage decode_texture_image(const std::vector<unsigned char>& bytes,
                                  const std::filesystem::path& name, bool raw) {
    const std::string context = "cannot read texture '" + name.string() + "'";
    TextureImage out;
    if (lower_extension(name) == ".exr") {
        Image img;
        try {
            img = decode_exr(bytes, name.string());
        } catch (const ImageError& e) {
            throw ImageError("texture: " + std::string(e.what()));
        }
        check_size(img.width, img.height, context);
        out.width = static_cast<std::uint32_t>(img.width);
        out.height = static_cast<std::uint32_t>(img.height);
        pack_floats(img.rgb.data(), img.rgb.size() / 3, out, context);
        return out;
    }
    if (bytes.size() > static_cast<std::size_t>(INT_MAX))
        throw ImageError(context + ": the file is larger than 2 GiB");
    const auto* data = bytes.data();
    const int size = static_cast<int>(bytes.size());
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(data, size, &width, &height, &channels))
        throw ImageError(context + ": not an image wavepath can decode (" +
                         std::string(stbi_failure_reason() ? stbi_failure_reason() : "unknown") +
                         "; textures are PNG, JPEG, BMP, TGA, PPM, HDR or EXR)");
    // Checked before decoding, so that a huge image is refused without
    // allocating it.
    check_size(width, height, context);
    out.width = static_cast<std::uint32_t>(width);
    out.height = static_cast<std::uint32_t>(height);
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    StbPixels pixels;
    if (stbi_is_hdr_from_memory(data, size)) {
        pixels.data = stbi_loadf_from_memory(data, size, &width, &height, &channels, 3);
        if (!pixels.data)
            throw ImageError(context + ": " + stbi_failure_reason());
        pack_floats(static_cast<const float*>(pixels.data), texels, out, context);
        return out;
    }
    if (stbi_is_16_bit_from_memory(data, size)) {
        pixels.data = stbi_load_16_from_memory(data, size, &width, &height, &channels, 3);
        if (!pixels.data)
            throw ImageError(context + ": " + stbi_failure_reason());
        const auto* p = static_cast<const std::uint16_t*>(pixels.data);
        std::vector<float> rgb(texels * 3);
        for (std::size_t i = 0; i < rgb.size(); ++i) {
            const double c = p[i] / 65535.0;
            rgb[i] = static_cast<float>(raw ? c : srgb_to_linear(c));
        }
        pack_floats(rgb.data(), texels, out, context);
        return out;
    }
    pixels.data = stbi_load_from_memory(data, size, &width, &height, &channels, 4);
    if (!pixels.data)
        throw ImageError(context + ": " + stbi_failure_reason());
    out.encoding = raw ? TexelEncoding::Linear8 : TexelEncoding::Srgb8;
    const auto* p = static_cast<const unsigned char*>(pixels.data);
    out.texels.resize(texels);
    for (std::size_t i = 0; i < texels; ++i) // alpha (the high byte) is dropped
        out.texels[i] = std::uint32_t{p[4 * i]} | std::uint32_t{p[4 * i + 1]} << 8 |
                        std::uint32_t{p[4 * i + 2]} << 16;
    return out;
}

double srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

namespace {

// The sRGB decoding of every 8-bit value, computed once: a 16384^2 image's
// mean would otherwise take 805 million pow() calls.
const std::array<double, 256>& srgb_table() {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i)
            t[static_cast<std::size_t>(i)] = srgb_to_linear(i / 255.0);
        return t;
    }();
    return table;
}

} // namespace

glm::dvec3 linear_texel(const TextureImage& image, std::size_t x, std::size_t y) {
    const std::size_t i = y * image.width + x;
    if (image.encoding == TexelEncoding::Float32)
        return {std::bit_cast<float>(image.texels[3 * i]),
                std::bit_cast<float>(image.texels[3 * i + 1]),
                std::bit_cast<float>(image.texels[3 * i + 2])};
    const std::uint32_t bits = image.texels[i];
    if (image.encoding == TexelEncoding::Srgb8) {
        const std::array<double, 256>& t = srgb_table();
        return {t[bits & 255u], t[(bits >> 8) & 255u], t[(bits >> 16) & 255u]};
    }
    return {(bits & 255u) / 255.0, ((bits >> 8) & 255u) / 255.0, ((bits >> 16) & 255u) / 255.0};
}

TextureImage read_texture_image(const std::filesystem::path& path, bool raw) {
    return decode_texture_image(read_file_bytes(path), path, raw);
}

} // namespace wp
