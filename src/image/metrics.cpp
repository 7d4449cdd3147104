#include "image/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

double mse(const Image& a, const Image& ref) {
    check_comparable(a, ref, "MSE");
    return mean_over(a, ref, [](double x, double r) { return (x - r) * (x - r); });
}

std::array<double, 3> mean_relative_bias(const Image& a, const Image& ref) {
    check_comparable(a, ref, "mean relative bias");
    std::array<double, 3> sum_a{}, sum_ref{};
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        sum_a[i % 3] += static_cast<double>(a.rgb[i]);
        sum_ref[i % 3] += static_cast<double>(ref.rgb[i]);
    }
    std::array<double, 3> bias{};
    for (std::size_t c = 0; c < 3; ++c)
        bias[c] = sum_ref[c] != 0.0 ? (sum_a[c] - sum_ref[c]) / sum_ref[c]
                                    : std::numeric_limits<double>::quiet_NaN();
    return bias;
}

namespace {

// n_even n_odd / n^2: turns (even - odd)^2 into an estimate of the variance of the
// full mean (see metrics.hpp).
double halves_factor(std::uint64_t n_even, std::uint64_t n_odd, const char* metric) {
    if (n_even == 0 || n_odd == 0)
        throw ImageError(std::string("cannot compute ") + metric +
                         ": each half needs at least one sample (have " + std::to_string(n_even) +
                         " and " + std::to_string(n_odd) + ")");
    const double e = static_cast<double>(n_even), o = static_cast<double>(n_odd);
    return e * o / ((e + o) * (e + o));
}

} // namespace

double mse_from_halves(const Image& even, const Image& odd, std::uint64_t n_even,
                       std::uint64_t n_odd) {
    check_comparable(even, odd, "MSE from half images");
    const double k = halves_factor(n_even, n_odd, "MSE from half images");
    return k * mean_over(even, odd, [](double x, double y) { return (x - y) * (x - y); });
}

double rel_mse_from_halves(const Image& even, const Image& odd, std::uint64_t n_even,
                           std::uint64_t n_odd) {
    check_comparable(even, odd, "relative MSE from half images");
    const double k = halves_factor(n_even, n_odd, "relative MSE from half images");
    const double we = static_cast<double>(n_even) / static_cast<double>(n_even + n_odd);
    const auto mean = [&](int x, int y, int c) {
        return we * static_cast<double>(even.pixel(x, y)[c]) +
               (1.0 - we) * static_cast<double>(odd.pixel(x, y)[c]);
    };
    const int w = even.width, h = even.height;
    double sum = 0.0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) {
                double r = 0.0; // 3x3 box mean of the full mean, clipped to the image
                int n = 0;
                for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy) {
                    for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx) {
                        r += mean(xx, yy, c);
                        ++n;
                    }
                }
                r /= n;
                const double d = static_cast<double>(even.pixel(x, y)[c]) -
                                 static_cast<double>(odd.pixel(x, y)[c]);
                sum += k * d * d / (r * r + 0.01);
            }
        }
    }
    return sum / static_cast<double>(even.rgb.size());
}

Image rel_error_map(const Image& a, const Image& ref) {
    check_comparable(a, ref, "relative error map");
    Image map(a.width, a.height);
    for (std::size_t p = 0; p < a.rgb.size(); p += 3) {
        double sum = 0.0;
        for (std::size_t c = 0; c < 3; ++c) {
            const double x = static_cast<double>(a.rgb[p + c]);
            const double r = static_cast<double>(ref.rgb[p + c]);
            sum += std::isfinite(x) && std::isfinite(r) ? (x - r) * (x - r) / (r * r + 0.01)
                                                        : std::numeric_limits<double>::quiet_NaN();
        }
        const auto value = static_cast<float>(sum / 3.0);
        map.rgb[p] = map.rgb[p + 1] = map.rgb[p + 2] = value;
    }
    return map;
}

std::size_t count_nonfinite(const Image& img) {
    check_image_shape(img, "cannot count non-finite values", /*require_pixels=*/false);
    return static_cast<std::size_t>(
        std::count_if(img.rgb.begin(), img.rgb.end(), [](float v) { return !std::isfinite(v); }));
}

} // namespace wp
