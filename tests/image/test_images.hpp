// Small test images whose every value is distinct, so a swapped channel, a flipped row
// or a transposed pixel changes the result.
#pragma once

#include "image/image.hpp"

#include <cstring>
#include <limits>

namespace wp::test {

// Value = 100 * (channel + 1) + 10 * y + x + 0.125: channel, row and column can be read
// off the number.
inline Image distinct_image(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) {
                img.pixel(x, y)[c] = static_cast<float>(100 * (c + 1) + 10 * y + x) + 0.125f;
            }
        }
    }
    return img;
}

// distinct_image plus values a lossy or sloppy writer would alter: negative zero,
// infinities, NaN, a denormal and a value that needs all 24 mantissa bits.
inline Image tricky_image() {
    Image img = distinct_image(3, 2);
    img.pixel(0, 0)[0] = -0.0f;
    img.pixel(1, 0)[1] = std::numeric_limits<float>::infinity();
    img.pixel(2, 0)[2] = -std::numeric_limits<float>::infinity();
    img.pixel(0, 1)[1] = std::numeric_limits<float>::quiet_NaN();
    img.pixel(1, 1)[0] = std::numeric_limits<float>::denorm_min();
    img.pixel(2, 1)[1] = 1.0f + std::numeric_limits<float>::epsilon();
    img.pixel(2, 1)[2] = -3.0e-7f;
    return img;
}

// Bitwise comparison, so NaN equals NaN and -0 differs from +0.
inline bool bit_identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
           std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

} // namespace wp::test
