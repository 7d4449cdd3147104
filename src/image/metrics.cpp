#include "image/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace wp {
namespace {

void check_comparable(const Image& a, const Image& ref, const char* metric) {
    const std::string context = std::string("cannot compute ") + metric;
    check_image_shape(a, context + " (image)");
    check_image_shape(ref, context + " (reference)");
    if (a.width != ref.width || a.height != ref.height) {
        throw ImageError(context + ": image is " + std::to_string(a.width) + "x" +
                         std::to_string(a.height) + " but reference is " +
                         std::to_string(ref.width) + "x" + std::to_string(ref.height));
    }
}

// Mean of term(a, r) over every channel value; accumulated in double so large images
// do not lose the small per-pixel contributions.
template <typename Term> double mean_over(const Image& a, const Image& ref, Term term) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        sum += term(static_cast<double>(a.rgb[i]), static_cast<double>(ref.rgb[i]));
    }
    return sum / static_cast<double>(a.rgb.size());
}

} // namespace

double rmse(const Image& a, const Image& ref) {
    check_comparable(a, ref, "RMSE");
    return std::sqrt(mean_over(a, ref, [](double x, double r) { return (x - r) * (x - r); }));
}

double rel_mse(const Image& a, const Image& ref) {
    check_comparable(a, ref, "relative MSE");
    return mean_over(a, ref, [](double x, double r) { return (x - r) * (x - r) / (r * r + 0.01); });
}

std::size_t count_nonfinite(const Image& img) {
    check_image_shape(img, "cannot count non-finite values", /*require_pixels=*/false);
    return static_cast<std::size_t>(
        std::count_if(img.rgb.begin(), img.rgb.end(), [](float v) { return !std::isfinite(v); }));
}

} // namespace wp
