// View transforms: linear radiance to 8-bit display values for PNG output.
#pragma once

#include "image/image.hpp"

#include <cstdint>
#include <vector>

namespace wp {

enum class ToneMap {
    // Exposure, clamp to [0, 1], sRGB transfer curve: the standard display view.
    Srgb,
    // The student report's view: sqrt(value) / max over the image of sqrt(value), times
    // 255.99 and truncated. Normalising by the maximum makes exposure irrelevant here.
    Seed,
};

struct ViewOptions {
    ToneMap tonemap = ToneMap::Srgb;
    double exposure_stops = 0.0; // linear values are multiplied by 2^exposure_stops (Srgb)
};

// Returns width * height * 3 bytes (r, g, b), top row first. NaN, infinite and (for
// Seed) negative values map to 0. Throws ImageError for a mis-sized image or a
// non-finite exposure.
std::vector<std::uint8_t> to_rgb8(const Image& img, const ViewOptions& view);

} // namespace wp
