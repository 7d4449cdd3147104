// A float RGB image (TexelEncoding::Float32) from linear colours, row by
// row, for the tests of textures and environment maps.
#pragma once

#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "image/texture_image.hpp"

namespace wp::test {

inline std::shared_ptr<const TextureImage> float_image(std::uint32_t w, std::uint32_t h,
                                                       const std::vector<glm::dvec3>& texels) {
    auto image = std::make_shared<TextureImage>();
    image->width = w;
    image->height = h;
    image->encoding = TexelEncoding::Float32;
    for (const glm::dvec3& c : texels)
        for (int k = 0; k < 3; ++k)
            image->texels.push_back(std::bit_cast<std::uint32_t>(static_cast<float>(c[k])));
    return image;
}

} // namespace wp::test
