// <spectrum> wavelength:value pairs as RGB (scene/mitsuba/spectrum.hpp),
// against what Mitsuba 3.9.1 itself makes of them and against invariants.
//
// The Mitsuba figures were printed by its Python binding (scalar_rgb, which
// computes in float32), e.g. for mitsuba-data's cbox.xml red wall:
//   import mitsuba as mi; mi.set_variant("scalar_rgb")
//   mi.spectrum_list_to_srgb(wavelengths, values, True, True)   # a reflectance
//   mi.spectrum_list_to_srgb(wavelengths, values, False, False) # a radiance
// (Mitsuba's XML reader calls it with bounded = not an emitter and d65 = not
// an emitter; an eta or k is unbounded with d65.)
#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "scene/mitsuba/spectrum.hpp"

using wp::mitsuba::spectrum_to_rgb;
using wp::mitsuba::SpectrumUse;

namespace {

// mitsuba-data's scenes/cbox/cbox.xml, its red wall and its light, as written there.
const std::vector<std::pair<double, double>> kRed = {
    {400, 0.04},  {404, 0.046}, {408, 0.048}, {412, 0.053}, {416, 0.049}, {420, 0.05},
    {424, 0.053}, {428, 0.055}, {432, 0.057}, {436, 0.056}, {440, 0.059}, {444, 0.057},
    {448, 0.061}, {452, 0.061}, {456, 0.06},  {460, 0.062}, {464, 0.062}, {468, 0.062},
    {472, 0.061}, {476, 0.062}, {480, 0.06},  {484, 0.059}, {488, 0.057}, {492, 0.058},
    {496, 0.058}, {500, 0.058}, {504, 0.056}, {508, 0.055}, {512, 0.056}, {516, 0.059},
    {520, 0.057}, {524, 0.055}, {528, 0.059}, {532, 0.059}, {536, 0.058}, {540, 0.059},
    {544, 0.061}, {548, 0.061}, {552, 0.063}, {556, 0.063}, {560, 0.067}, {564, 0.068},
    {568, 0.072}, {572, 0.08},  {576, 0.09},  {580, 0.099}, {584, 0.124}, {588, 0.154},
    {592, 0.192}, {596, 0.255}, {600, 0.287}, {604, 0.349}, {608, 0.402}, {612, 0.443},
    {616, 0.487}, {620, 0.513}, {624, 0.558}, {628, 0.584}, {632, 0.62},  {636, 0.606},
    {640, 0.609}, {644, 0.651}, {648, 0.612}, {652, 0.61},  {656, 0.65},  {660, 0.638},
    {664, 0.627}, {668, 0.62},  {672, 0.63},  {676, 0.628}, {680, 0.642}, {684, 0.639},
    {688, 0.657}, {692, 0.639}, {696, 0.635}, {700, 0.642}};
const std::vector<std::pair<double, double>> kLight = {
    {400, 0.0}, {500, 8.0}, {600, 15.6}, {700, 18.4}};

glm::dvec3 convert(const std::vector<std::pair<double, double>>& pairs, SpectrumUse use,
                   double scale = 1.0) {
    std::vector<double> wavelengths, values;
    for (const auto& [w, v] : pairs) {
        wavelengths.push_back(w);
        values.push_back(v * scale);
    }
    return spectrum_to_rgb(wavelengths, values, use);
}

// Mitsuba's float32 sum of 1000 terms against this double one: 1e-5 of the value.
void check_mitsuba(const glm::dvec3& ours, const glm::dvec3& mitsuba) {
    INFO("wavepath " << ours.x << " " << ours.y << " " << ours.z << ", Mitsuba " << mitsuba.x << " "
                     << mitsuba.y << " " << mitsuba.z);
    for (int c = 0; c < 3; ++c)
        CHECK(ours[c] == Approx(mitsuba[c]).epsilon(1e-5));
}

} // namespace

TEST_CASE("mitsuba spectrum: Mitsuba 3's own RGB of mitsuba-data's Cornell box spectra",
          "[scene][mitsuba][spectrum]") {
    check_mitsuba(convert(kRed, SpectrumUse::Reflectance), {0.49132, 0.049228, 0.0509219});
    check_mitsuba(convert(kLight, SpectrumUse::Emission), {20.7108, 10.8546, 2.77115});
    // The luminaire's flat 0.78 over 400..700 nm: near grey, not exactly
    // (the ends of the visible range are left out).
    check_mitsuba(
        convert({{400, 0.78}, {500, 0.78}, {600, 0.78}, {700, 0.78}}, SpectrumUse::Reflectance),
        {0.776368, 0.779809, 0.776029});
    // An index of refraction: D65-weighed, not clamped above 1.
    check_mitsuba(convert({{400, 0.2}, {550, 0.9}, {700, 3.5}}, SpectrumUse::Unbounded),
                  {2.36491, 0.913256, 0.362788});
}

TEST_CASE("mitsuba spectrum: a flat reflectance is a grey of its value, a radiance scales",
          "[scene][mitsuba][spectrum]") {
    // Over the whole table (360..830 nm) under D65, whose white is sRGB's:
    // grey to 0.2 % (the 1000-step sum and the tables' rounding; Mitsuba
    // gives 0.299695 0.299662 0.299641 for 0.3).
    for (const double v : {0.1, 0.3, 0.9}) {
        const glm::dvec3 rgb = convert({{360, v}, {830, v}}, SpectrumUse::Reflectance);
        for (int c = 0; c < 3; ++c)
            CHECK(rgb[c] == Approx(v).epsilon(2e-3));
    }
    // Emission is linear in the spectrum (no clamp above), reflectance clamps at 1.
    const glm::dvec3 once = convert(kLight, SpectrumUse::Emission);
    const glm::dvec3 thrice = convert(kLight, SpectrumUse::Emission, 3.0);
    for (int c = 0; c < 3; ++c)
        CHECK(thrice[c] == Approx(3.0 * once[c]).epsilon(1e-12));
    CHECK(convert({{360, 5.0}, {830, 5.0}}, SpectrumUse::Reflectance) == glm::dvec3(1.0));
    // Outside the colour matching functions' range, nothing is seen.
    CHECK(convert({{900, 1.0}, {1000, 1.0}}, SpectrumUse::Emission) == glm::dvec3(0.0));
    // A pure red spectrum's negative sRGB channels clamp to 0 (Mitsuba's
    // "clamping out-of-gamut color").
    const glm::dvec3 deep_red = convert({{640, 1.0}, {660, 1.0}}, SpectrumUse::Emission);
    CHECK(deep_red.x > 0.0);
    CHECK(deep_red.y == 0.0);
}
