#include "image/exposure.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace wp {
namespace {

// The q-quantile (nearest rank) of values; reorders them. Not empty.
double quantile(std::vector<double>& values, double q) {
    const double last = static_cast<double>(values.size() - 1);
    const auto rank = static_cast<std::size_t>(std::lround(q * last));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank),
                     values.end());
    return values[rank];
}

} // namespace

double luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

AutoExposure auto_exposure(const Image& img, double emitter_luminance) {
    check_image_shape(img, "cannot choose an exposure", /*require_pixels=*/false);
    AutoExposure result;
    std::vector<double> luminances, brightest_channels;
    for (std::size_t p = 0; p < img.rgb.size(); p += 3) {
        const double r = img.rgb[p], g = img.rgb[p + 1], b = img.rgb[p + 2];
        const double y = luminance(r, g, b);
        if (!std::isfinite(y) || !(y > 0.0))
            continue;
        if (y >= emitter_luminance) {
            ++result.emitters;
            continue;
        }
        luminances.push_back(y);
        brightest_channels.push_back(std::max({r, g, b}));
    }
    result.counted = luminances.size();
    if (luminances.empty())
        return result; // black, or all emitter: no exposure shows more than another
    const double median = quantile(luminances, 0.5);
    const double highlight = quantile(brightest_channels, kHighlightQuantile);
    result.key_scale = kMidGrey / median;
    // A counted pixel has positive luminance, so a positive channel.
    result.highlight_scale = 1.0 / highlight;
    result.scale = std::min(result.key_scale, result.highlight_scale);
    return result;
}

} // namespace wp
