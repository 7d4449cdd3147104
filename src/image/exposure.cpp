#include "image/exposure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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

// The values of a 3x3 neighbourhood, kept sorted as they come (at most 9:
// insertion is the fastest sort here).
class Window {
  public:
    void add(double value) {
        std::size_t i = size_++;
        for (; i > 0 && values_[i - 1] > value; --i)
            values_[i] = values_[i - 1];
        values_[i] = value;
    }
    // The same nearest rank as quantile(values, 0.5).
    double median() const {
        return values_[static_cast<std::size_t>(std::lround(0.5 * static_cast<double>(size_ - 1)))];
    }

  private:
    std::array<double, 9> values_{};
    std::size_t size_ = 0;
};

} // namespace

double luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

AutoExposure auto_exposure(const Image& img, double emitter_luminance) {
    check_image_shape(img, "cannot choose an exposure", /*require_pixels=*/false);
    AutoExposure result;
    // Per pixel: luminance and brightest channel, or NaN for a pixel that
    // takes no part (an emitter, or a non-finite value).
    const std::size_t pixels = img.rgb.size() / 3;
    std::vector<double> luminance_of(pixels), brightest_of(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        const double r = img.rgb[3 * i], g = img.rgb[3 * i + 1], b = img.rgb[3 * i + 2];
        const double y = luminance(r, g, b);
        const bool emitter = std::isfinite(y) && y >= emitter_luminance;
        result.emitters += emitter;
        const bool takes_part = std::isfinite(y) && !emitter;
        luminance_of[i] = takes_part ? y : std::nan("");
        brightest_of[i] = takes_part ? std::max({r, g, b}) : std::nan("");
    }
    // The statistics are of the image seen through a 3x3 median filter: at a
    // few samples per pixel, light found through a mirror or a small gap
    // shows as isolated bright pixels (fireflies), which can be more than
    // 1 % of the image and would set the highlight quantile; the filter
    // removes them and keeps regions of two pixels or more across.
    std::vector<double> luminances, brightest_channels;
    luminances.reserve(pixels);
    brightest_channels.reserve(pixels);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * img.width + x;
            if (!(luminance_of[i] > 0.0))
                continue; // black pixels carry no information about exposure
            Window window_y, window_max;
            for (int v = std::max(y - 1, 0); v <= std::min(y + 1, img.height - 1); ++v)
                for (int u = std::max(x - 1, 0); u <= std::min(x + 1, img.width - 1); ++u) {
                    const std::size_t j = static_cast<std::size_t>(v) * img.width + u;
                    if (!std::isnan(luminance_of[j])) {
                        window_y.add(luminance_of[j]);
                        window_max.add(brightest_of[j]);
                    }
                }
            luminances.push_back(window_y.median());
            brightest_channels.push_back(window_max.median());
        }
    result.counted = luminances.size();
    if (luminances.empty())
        return result; // black, or all emitter: no exposure shows more than another
    const double median = quantile(luminances, 0.5);
    const double highlight = quantile(brightest_channels, kHighlightQuantile);
    // Filtered values may be 0 (a lit pixel among black ones); a zero
    // statistic sets no bound.
    constexpr double kNoBound = std::numeric_limits<double>::infinity();
    result.key_scale = median > 0.0 ? kMidGrey / median : kNoBound;
    result.highlight_scale = highlight > 0.0 ? 1.0 / highlight : kNoBound;
    result.scale = std::min(result.key_scale, result.highlight_scale);
    if (result.scale == kNoBound)
        result.scale = 1.0;
    return result;
}

} // namespace wp
