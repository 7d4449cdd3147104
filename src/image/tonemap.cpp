#include "image/tonemap.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace wp {
namespace {

// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1].
double srgb_encode(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::uint8_t srgb_byte(float value, double scale) {
    if (!std::isfinite(value)) {
        return 0;
    }
    const double v = static_cast<double>(value) * scale;
    // Written so NaN (0 * inf when the exposure is huge) also lands on 0.
    if (!(v > 0.0)) {
        return 0;
    }
    if (v >= 1.0) {
        return 255;
    }
    return static_cast<std::uint8_t>(std::lround(srgb_encode(v) * 255.0));
}

std::vector<std::uint8_t> srgb_view(const Image& img, double exposure_stops) {
    const double scale = std::exp2(exposure_stops);
    std::vector<std::uint8_t> out(img.rgb.size());
    std::transform(img.rgb.begin(), img.rgb.end(), out.begin(),
                   [scale](float v) { return srgb_byte(v, scale); });
    return out;
}

// sqrt of a value the Seed view can show; everything else counts as black.
double seed_sqrt(float value) {
    return std::isfinite(value) && value > 0.0f ? std::sqrt(static_cast<double>(value)) : 0.0;
}

std::vector<std::uint8_t> seed_view(const Image& img) {
    double max_sqrt = 0.0;
    for (const float v : img.rgb) {
        max_sqrt = std::max(max_sqrt, seed_sqrt(v));
    }
    std::vector<std::uint8_t> out(img.rgb.size(), 0);
    if (max_sqrt == 0.0) {
        return out; // all black: avoid 0 / 0
    }
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        // Truncation (not rounding) matches the report; 255.99 keeps the maximum at 255.
        const double scaled = seed_sqrt(img.rgb[i]) / max_sqrt * 255.99;
        out[i] = static_cast<std::uint8_t>(std::clamp(scaled, 0.0, 255.0));
    }
    return out;
}

} // namespace

std::vector<std::uint8_t> to_rgb8(const Image& img, const ViewOptions& view) {
    check_image_shape(img, "cannot tone map image", /*require_pixels=*/false);
    if (!std::isfinite(view.exposure_stops)) {
        throw ImageError("cannot tone map image: exposure must be finite, got " +
                         std::to_string(view.exposure_stops));
    }
    switch (view.tonemap) {
    case ToneMap::Srgb:
        return srgb_view(img, view.exposure_stops);
    case ToneMap::Seed:
        return seed_view(img);
    }
    throw ImageError("cannot tone map image: unknown tone map " +
                     std::to_string(static_cast<int>(view.tonemap)));
}

} // namespace wp
