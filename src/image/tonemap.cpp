#include "image/tonemap.hpp"

#include "image/exposure.hpp"
#include "image/filmic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace wp {
namespace {

// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1].
double srgb_encode(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// A linear display value as its sRGB byte; values past [0, 1] clip. Written
// so NaN (0 * inf when the exposure is huge) also lands on 0.
std::uint8_t display_byte(double v) {
    if (!(v > 0.0))
        return 0;
    if (v >= 1.0)
        return 255;
    return static_cast<std::uint8_t>(std::lround(srgb_encode(v) * 255.0));
}

// An exposed value; non-finite input counts as black.
double exposed(float value, double scale) {
    return std::isfinite(value) ? static_cast<double>(value) * scale : 0.0;
}

std::vector<std::uint8_t> srgb_view(const Image& img, double scale) {
    std::vector<std::uint8_t> out(img.rgb.size());
    std::transform(img.rgb.begin(), img.rgb.end(), out.begin(),
                   [scale](float v) { return display_byte(exposed(v, scale)); });
    return out;
}

std::vector<std::uint8_t> filmic_view(const Image& img, double scale) {
    std::vector<std::uint8_t> out(img.rgb.size());
    for (std::size_t p = 0; p < img.rgb.size(); p += 3) {
        std::array<double, 3> rgb{};
        for (std::size_t c = 0; c < 3; ++c) {
            const double v = exposed(img.rgb[p + c], scale);
            rgb[c] = v > 0.0 ? std::min(v, 1e30) : 0.0; // NaN and negatives are black
        }
        const std::array<double, 3> display = aces_filmic(rgb);
        for (std::size_t c = 0; c < 3; ++c)
            out[p + c] = display_byte(display[c]);
    }
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

void check_exposure(const ViewOptions& view) {
    if (!std::isfinite(view.exposure_stops)) {
        throw ImageError("cannot tone map image: exposure must be finite, got " +
                         std::to_string(view.exposure_stops));
    }
}

} // namespace

std::string to_string(ToneMap tonemap) {
    switch (tonemap) {
    case ToneMap::Srgb:
        return "srgb";
    case ToneMap::Seed:
        return "seed";
    case ToneMap::Filmic:
        return "filmic";
    }
    return "unknown";
}

double exposure_scale(const Image& img, const ViewOptions& view) {
    check_exposure(view);
    const double offset = std::exp2(view.exposure_stops);
    if (view.exposure == Exposure::Fixed)
        return offset;
    return auto_exposure(img, view.emitter_luminance).scale * offset;
}

std::vector<std::uint8_t> to_rgb8(const Image& img, const ViewOptions& view) {
    check_image_shape(img, "cannot tone map image", /*require_pixels=*/false);
    switch (view.tonemap) {
    case ToneMap::Srgb:
        return srgb_view(img, exposure_scale(img, view));
    case ToneMap::Filmic:
        return filmic_view(img, exposure_scale(img, view));
    case ToneMap::Seed:
        check_exposure(view); // the same check of the options, though Seed ignores them
        return seed_view(img);
    }
    throw ImageError("cannot tone map image: unknown tone map " +
                     std::to_string(static_cast<int>(view.tonemap)));
}

std::string describe_view(const Image& img, const ViewOptions& view) {
    if (view.tonemap == ToneMap::Seed)
        return "seed (sqrt, divided by the image maximum; no exposure)";
    char text[160];
    const double stops = std::log2(exposure_scale(img, view));
    if (view.exposure == Exposure::Fixed)
        std::snprintf(text, sizeof text, "%s, exposure %+.6g stops (fixed)",
                      to_string(view.tonemap).c_str(), stops);
    else
        std::snprintf(text, sizeof text, "%s, exposure %+.6g stops (automatic %+.6g, offset %+.6g)",
                      to_string(view.tonemap).c_str(), stops, stops - view.exposure_stops,
                      view.exposure_stops);
    return text;
}

} // namespace wp
