#include "image/filmic.hpp"

#include <algorithm>

namespace wp {
namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

// sRGB -> XYZ -> D65 to D60 -> AP1 -> the reference rendering's saturation.
constexpr Matrix kAcesInput = {
    {{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}}};
// The output transform's saturation -> XYZ -> D60 to D65 -> sRGB.
constexpr Matrix kAcesOutput = {
    {{1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}}};

std::array<double, 3> multiply(const Matrix& m, const std::array<double, 3>& v) {
    std::array<double, 3> out{};
    for (std::size_t i = 0; i < 3; ++i)
        out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return out;
}

// The rational fit of the reference rendering and output transforms' tone
// curve, per AP1 channel.
double rrt_and_odt_fit(double v) {
    const double a = v * (v + 0.0245786) - 0.000090537;
    const double b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return a / b;
}

} // namespace

std::array<double, 3> aces_filmic(const std::array<double, 3>& linear) {
    std::array<double, 3> v = multiply(kAcesInput, linear);
    for (double& c : v)
        c = rrt_and_odt_fit(c);
    v = multiply(kAcesOutput, v);
    for (double& c : v)
        c = std::clamp(c, 0.0, 1.0);
    return v;
}

} // namespace wp
