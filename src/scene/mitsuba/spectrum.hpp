// A <spectrum> of wavelength:value pairs as the RGB colour Mitsuba 3's RGB
// variants make of it (Mitsuba 3.9.1's spectrum_list_to_srgb, called from
// its Properties::get_texture): the piecewise-linear spectrum integrated
// against the CIE 1931 colour matching functions (cie_1931_table.hpp), the
// result in linear sRGB. How it is weighed and clamped depends on what the
// spectrum is, which only the plugin that reads it knows (SpectrumUse).
#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace wp::mitsuba {

enum class SpectrumUse {
    // A reflectance or a texture's colour: under the D65 illuminant, so that
    // a flat spectrum is a grey of its value; clamped to [0, 1].
    Reflectance,
    // An index of refraction (eta, k): under D65, clamped below at 0 only.
    Unbounded,
    // An emitter's radiance, intensity or irradiance: the spectrum itself
    // (it is the light), clamped below at 0.
    Emission,
};

// `wavelengths` (nm) strictly increasing, at least two, one value each (the
// XML reader checks both). Mitsuba's method, step by step: 1000 wavelengths
// evenly spaced over 360..830 nm (ends included); those outside the given
// range are left out (the spectrum is 0 there); at each, the spectrum
// interpolated linearly between its pairs, times the colour matching
// functions (and D65 unless Emission), both linear between their 5 nm
// samples; the sum times 470 / 1000 nm and 1 / the integral of y-bar is XYZ,
// which Mitsuba's XYZ-to-sRGB matrix turns into linear sRGB.
glm::dvec3 spectrum_to_rgb(const std::vector<double>& wavelengths,
                           const std::vector<double>& values, SpectrumUse use);

} // namespace wp::mitsuba
