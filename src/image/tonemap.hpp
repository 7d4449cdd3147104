// View transforms: linear radiance to 8-bit display values for PNG output.
#pragma once

#include "image/image.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace wp {

enum class ToneMap {
    // Exposure, clamp to [0, 1], sRGB transfer curve: the standard display view.
    Srgb,
    // The student report's view: sqrt(value) / max over the image of sqrt(value), times
    // 255.99 and truncated. Normalising by the maximum makes exposure irrelevant here.
    Seed,
    // Exposure, then ACES's filmic curve (Stephen Hill's fit of the reference
    // rendering and sRGB output transforms, filmic.hpp), then the sRGB curve:
    // highlights roll off instead of clipping.
    Filmic,
};

enum class Exposure {
    // Chosen from the image (exposure.hpp); exposure_stops is an offset from it.
    Auto,
    // exposure_stops itself: the same input gives the same bytes in every image,
    // for pipelines that compare views of several renders.
    Fixed,
};

struct ViewOptions {
    ToneMap tonemap = ToneMap::Srgb;
    Exposure exposure = Exposure::Auto;
    // Linear values are multiplied by 2^exposure_stops (Fixed) or by the
    // automatic exposure times 2^exposure_stops (Auto). Seed ignores it.
    double exposure_stops = 0.0;
    // Auto: the luminance from which a pixel counts as an emitter seen
    // directly or in a mirror, left out of the exposure's statistics
    // (auto_exposure). Renders set it from the scene (app/view_cli.hpp).
    double emitter_luminance = std::numeric_limits<double>::infinity();

    static ViewOptions fixed(double stops, ToneMap tonemap = ToneMap::Srgb) {
        ViewOptions view;
        view.tonemap = tonemap;
        view.exposure = Exposure::Fixed;
        view.exposure_stops = stops;
        return view;
    }
};

// "srgb", "seed", "filmic": the names the command line takes.
std::string to_string(ToneMap tonemap);

// The factor linear values are multiplied by before the curve: 2^stops, or
// the automatic exposure of img times 2^stops. Throws ImageError for a
// non-finite exposure_stops.
double exposure_scale(const Image& img, const ViewOptions& view);

// Returns width * height * 3 bytes (r, g, b), top row first. NaN, infinite and (for
// Seed) negative values map to 0. Throws ImageError for a mis-sized image or a
// non-finite exposure.
std::vector<std::uint8_t> to_rgb8(const Image& img, const ViewOptions& view);

// A line that says how the view was made, e.g. "srgb, exposure -1.32 stops (automatic
// -1.32, offset +0)", for the PNG's metadata: --fixed-exposure with the stops
// given reproduces it.
std::string describe_view(const Image& img, const ViewOptions& view);

} // namespace wp
