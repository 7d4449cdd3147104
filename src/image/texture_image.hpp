// The texels of a bitmap texture's image file, as the kernels store them
// (WpTexture, kernels/wp_shared.h; kernels/textures/bitmap.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

namespace wp {

// How the texels are packed: 8 bits per channel in one uint (r in the low
// byte, then g, b), either sRGB-encoded (decoded per texel on the device,
// after the lookup picks it, so filtering happens in linear RGB) or already
// linear; or three float32 bit patterns per texel, linear.
enum class TexelEncoding { Srgb8, Linear8, Float32 };

struct TextureImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    TexelEncoding encoding = TexelEncoding::Srgb8;
    std::vector<std::uint32_t> texels; // row 0 is the top of the image

    std::size_t bytes() const { return texels.size() * sizeof(std::uint32_t); }
};

// sRGB's decoding curve (IEC 61966-2-1), as the kernels apply it
// (kernels/textures/bitmap.h).
double srgb_to_linear(double c);

// Texel (x, y) (in range) in linear RGB, decoded as the kernels decode it.
glm::dvec3 linear_texel(const TextureImage& image, std::size_t x, std::size_t y);

// The largest side a texture image may have, in texels.
inline constexpr std::uint32_t kMaxTextureSide = 16384;

// Reads a texture image. PNG, JPEG, BMP, TGA, PPM/PGM (stb_image) and
// Radiance HDR (.hdr, stb_image); OpenEXR (.exr, tinyexr, RGB channels).
// As Mitsuba 3 treats them: 8-bit files are sRGB-encoded unless `raw` (then
// their bytes are taken as linear values), 16-bit ones too (decoded here, on
// the host, to float), HDR and EXR files are linear. Grey images become
// grey RGB; an alpha channel is ignored. Throws FileError for a file that
// cannot be read and ImageError (one line naming the file) for one that
// cannot be decoded, that is empty or has a side above kMaxTextureSide, or
// has a non-finite or negative texel.
TextureImage read_texture_image(const std::filesystem::path& path, bool raw);

// The same for a file's bytes already in memory; `name` names it in messages
// and chooses the decoder by its extension (.exr) or the bytes' signature.
TextureImage decode_texture_image(const std::vector<unsigned char>& bytes,
                                  const std::filesystem::path& name, bool raw);

} // namespace wp
