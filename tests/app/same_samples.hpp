// Two renders of the same samples (same seed and spp) on different devices
// or processes: equal up to float rounding of the sums.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>

#include "image/image.hpp"

namespace wp::test::cli {

// Every sample's radiance is the same bits whichever device renders it; the
// devices add them in float32 batches of at most `spp` samples, grouped
// differently, and n non-negative floats sum with a rounding error of at
// most (n - 1) * 2^-24 of their total. So a pixel's two means differ by at
// most 2 * spp * 2^-24 of it, plus the rounding of the mean to float. A
// sample lost, counted twice or taken from another index moves pixels by
// far more.
inline void check_same_samples(const Image& image, const Image& reference, std::uint32_t spp) {
    REQUIRE(image.width == reference.width);
    REQUIRE(image.height == reference.height);
    const double relative = 2.0 * spp * std::ldexp(1.0, -24) + std::ldexp(1.0, -23);
    double worst = 0.0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        const double excess = std::abs(image.rgb[i] - reference.rgb[i]) /
                              (relative * std::abs(reference.rgb[i]) + 1e-37);
        if (excess > worst) {
            worst = excess;
            at = i;
        }
    }
    INFO("value " << at << ": " << image.rgb[at] << " against " << reference.rgb[at]);
    CHECK(worst <= 1.0);
}

} // namespace wp::test::cli
