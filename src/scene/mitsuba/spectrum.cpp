// Wavelength:value pairs to RGB, as Mitsuba 3's RGB mode (spectrum.hpp).
#include "scene/mitsuba/spectrum.hpp"

#include <algorithm>
#include <cstddef>

#include <glm/common.hpp>

#include "scene/mitsuba/cie_1931_table.hpp"

namespace wp::mitsuba {
namespace {

// The tables' sample at or before a wavelength, and how far past it the
// wavelength lies (0..1): Mitsuba's curves are linear between samples.
struct TablePlace {
    std::size_t index;
    double fraction;
};

TablePlace table_place(double wavelength) {
    const double t = (wavelength - cie::kFirstWavelength) / cie::kStep;
    const auto i = static_cast<std::size_t>(std::clamp(static_cast<int>(t), 0, cie::kSamples - 2));
    return {i, t - static_cast<double>(i)};
}

glm::dvec3 xyz_at(const TablePlace& at) {
    const auto& a = cie::kXyz[at.index];
    const auto& b = cie::kXyz[at.index + 1];
    return glm::dvec3(a[0], a[1], a[2]) * (1.0 - at.fraction) +
           glm::dvec3(b[0], b[1], b[2]) * at.fraction;
}

double d65_at(const TablePlace& at) {
    return cie::kD65[at.index] * (1.0 - at.fraction) + cie::kD65[at.index + 1] * at.fraction;
}

// Mitsuba's xyz_to_srgb (linear sRGB, D65 white).
glm::dvec3 xyz_to_linear_srgb(const glm::dvec3& xyz) {
    return {3.240479 * xyz.x - 1.537150 * xyz.y - 0.498535 * xyz.z,
            -0.969256 * xyz.x + 1.875991 * xyz.y + 0.041556 * xyz.z,
            0.055648 * xyz.x - 0.204043 * xyz.y + 1.057311 * xyz.z};
}

} // namespace

glm::dvec3 spectrum_to_rgb(const std::vector<double>& wavelengths,
                           const std::vector<double>& values, SpectrumUse use) {
    constexpr int kSteps = 1000;
    const double range = cie::kLastWavelength - cie::kFirstWavelength;
    glm::dvec3 xyz(0.0);
    for (int step = 0; step < kSteps; ++step) {
        const double w = cie::kFirstWavelength + step / double(kSteps - 1) * range;
        if (w < wavelengths.front() || w > wavelengths.back())
            continue;
        // The last pair at or before w, and the one after it.
        const auto above = std::upper_bound(wavelengths.begin(), wavelengths.end(), w);
        const std::size_t i = std::min(static_cast<std::size_t>(above - wavelengths.begin()),
                                       wavelengths.size() - 1) -
                              1;
        const double w0 = wavelengths[i], w1 = wavelengths[i + 1];
        const double value = ((w - w1) * values[i] + (w0 - w) * values[i + 1]) / (w0 - w1);
        const TablePlace at = table_place(w);
        const double illuminant = use == SpectrumUse::Emission ? 1.0 : d65_at(at);
        xyz += xyz_at(at) * (value * illuminant);
    }
    xyz *= range / kSteps * cie::kYNormalization;
    glm::dvec3 rgb = glm::max(xyz_to_linear_srgb(xyz), glm::dvec3(0.0));
    if (use == SpectrumUse::Reflectance)
        rgb = glm::min(rgb, glm::dvec3(1.0));
    return rgb;
}

} // namespace wp::mitsuba
