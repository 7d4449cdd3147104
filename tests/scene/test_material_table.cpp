// The host's material tables and the numbers it derives for the kernels.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "scene/material.hpp"

namespace {

// The unpolarised Fresnel reflectance of a dielectric interface at incidence
// cosine mu, eta = n_far / n_near (1 beyond the critical angle).
double fresnel(double mu, double eta) {
    const double sin2_t = (1.0 - mu * mu) / (eta * eta);
    if (sin2_t >= 1.0)
        return 1.0;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (mu - eta * cos_t) / (mu + eta * cos_t);
    const double rp = (eta * mu - cos_t) / (eta * mu + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// Its cosine-weighted hemispherical mean, 2 * integral of F(mu) mu dmu over
// [0, 1], by Simpson's rule.
double diffuse_fresnel(double eta) {
    constexpr int kSteps = 20000;
    double sum = 0.0;
    for (int i = 0; i <= kSteps; ++i) {
        const double w = (i == 0 || i == kSteps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        const double mu = double(i) / kSteps;
        sum += w * fresnel(mu, eta) * mu;
    }
    return 2.0 * sum / (3.0 * kSteps);
}

} // namespace

TEST_CASE("materials: the diffuse Fresnel reflectance fits the integral of Fresnel's law",
          "[scene][materials]") {
    // Mitsuba 3's fits, to their stated accuracy: d'Eon and Irving's above 1
    // (0.1 % up to 2, 0.2 % up to 10), Egan and Hilgeman's below (from inside
    // a denser medium; a few tenths of a percent for everyday indices).
    for (double eta : {1.05, 1.333, 1.49, 1.9, 2.419, 5.0}) {
        INFO("eta " << eta << ": fit " << wp::fresnel_diffuse_reflectance(eta) << ", integral "
                    << diffuse_fresnel(eta));
        // (Near 1 the reflectance itself vanishes: there the fit's error is
        // about 1e-4 absolute.)
        CHECK(std::fabs(wp::fresnel_diffuse_reflectance(eta) - diffuse_fresnel(eta)) <=
              std::max(1e-4, (eta <= 2.0 ? 1e-3 : 2e-3) * diffuse_fresnel(eta)));
    }
    for (double ior : {1.333, 1.49, 1.9}) {
        const double eta = 1.0 / ior;
        INFO("eta 1/" << ior << ": fit " << wp::fresnel_diffuse_reflectance(eta) << ", integral "
                      << diffuse_fresnel(eta));
        CHECK(std::fabs(wp::fresnel_diffuse_reflectance(eta) / diffuse_fresnel(eta) - 1.0) <= 6e-3);
    }
}

TEST_CASE("materials: the rough coating's tables are Mitsuba 3's", "[scene][material]") {
    // Mitsuba 3.9.1 (scalar_rgb), read back through its roughplastic's eval:
    // with specular_reflectance 0, eval(mu, mu) = rho' T(mu)^2 mu / (pi eta^2),
    // and R_int from the nonlinear base at two diffuse reflectances
    // (`python3 tools/mitsuba_roughplastic.py tables`). Mitsuba integrates in
    // float, so its values carry about 1e-6 of rounding; they are given to 6
    // places.
    struct Case {
        wp::MicrofacetDistribution distribution;
        double alpha, int_ior, internal_reflectance;
        double t[4]; // at mu = 1/63, 16/63, 40/63 and 1
    };
    const Case cases[] = {
        {wp::MicrofacetDistribution::Ggx,
         0.1,
         1.49,
         0.545523,
         {0.570511, 0.769269, 0.938501, 0.960893}},
        {wp::MicrofacetDistribution::Beckmann,
         0.3,
         1.49,
         0.523425,
         {0.687316, 0.809928, 0.933796, 0.961102}},
        {wp::MicrofacetDistribution::Ggx,
         0.7,
         2.4,
         0.409113,
         {0.459692, 0.582523, 0.710584, 0.783007}},
        // A coating of lower index than outside: grazing light is reflected
        // totally at every microfacet.
        {wp::MicrofacetDistribution::Beckmann, 0.05, 0.8, 0.050579, {0.0, 0.0, 0.714863, 0.987626}},
    };
    for (const Case& c : cases) {
        INFO("alpha " << c.alpha << ", int_ior " << c.int_ior);
        const wp::RoughCoating coating =
            wp::rough_coating(c.distribution, c.alpha, c.int_ior / 1.000277);
        REQUIRE(coating.transmittance.size() == WP_ROUGH_TRANSMITTANCE_RES);
        CHECK(coating.internal_reflectance == Approx(c.internal_reflectance).margin(5e-6));
        const int index[] = {1, 16, 40, 63};
        for (int i = 0; i < 4; ++i)
            CHECK(coating.transmittance[static_cast<std::size_t>(index[i])] ==
                  Approx(c.t[i]).margin(1e-5));
    }
}
