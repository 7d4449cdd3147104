// The convergence metrics (MSE, mean relative bias, error from half images, the
// error map) against values worked out by hand, and the half-image estimate
// against the variance it estimates on synthetic samples.
#include "image/metrics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

using wp::Image;

namespace {

Image make(int w, int h, std::vector<float> values) {
    Image img(w, h);
    img.rgb = std::move(values);
    return img;
}

// As in test_metrics.cpp: a = (1, 2, 3), (0, 0.5, -1); ref = (1, 1, 1), (0, 0, 0).
Image image_a() {
    return make(2, 1, {1.0f, 2.0f, 3.0f, 0.0f, 0.5f, -1.0f});
}
Image image_ref() {
    return make(2, 1, {1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f});
}

} // namespace

TEST_CASE("mse and mean relative bias by hand on a 2x1 image", "[metrics]") {
    // Squared differences 0, 1, 4, 0, 0.25, 1: sum 6.25 over 6 values.
    CHECK(wp::mse(image_a(), image_ref()) == Approx(6.25 / 6.0).epsilon(1e-12));
    CHECK(wp::mse(image_a(), image_ref()) ==
          Approx(std::pow(wp::rmse(image_a(), image_ref()), 2)).epsilon(1e-12));
    // Channel sums: image R 1, G 2.5, B 2; reference 1, 1, 1.
    const auto bias = wp::mean_relative_bias(image_a(), image_ref());
    CHECK(bias[0] == Approx(0.0).margin(1e-12));
    CHECK(bias[1] == Approx(1.5).epsilon(1e-12));
    CHECK(bias[2] == Approx(1.0).epsilon(1e-12));
    // A channel whose reference mean is zero has no relative bias.
    const auto undefined =
        wp::mean_relative_bias(image_a(), make(2, 1, {1.0f, 0.0f, 2.0f, 1.0f, 0.0f, 2.0f}));
    CHECK(undefined[0] == Approx(-0.5)); // sums 1 and 2
    CHECK(std::isnan(undefined[1]));
    CHECK(undefined[2] == Approx(-0.5)); // sums 3 - 1 = 2 and 2 + 2 = 4
}

TEST_CASE("mse_from_halves by hand: equal and unequal halves", "[metrics]") {
    const Image even = make(2, 1, {1, 2, 3, 4, 5, 6});
    const Image odd = make(2, 1, {0, 2, 5, 4, 3, 6});
    // Differences 1, 0, -2, 0, 2, 0: squares sum 9, mean 1.5.
    // Equal halves (2 and 2 samples): times 2 * 2 / 4^2 = 1/4.
    CHECK(wp::mse_from_halves(even, odd, 2, 2) == Approx(1.5 / 4.0).epsilon(1e-12));
    // 3 and 1 samples: times 3 * 1 / 4^2 = 3/16.
    CHECK(wp::mse_from_halves(even, odd, 3, 1) == Approx(1.5 * 3.0 / 16.0).epsilon(1e-12));
    CHECK(wp::mse_from_halves(even, even, 4, 4) == 0.0);
    CHECK_THROWS_AS(wp::mse_from_halves(even, odd, 2, 0), wp::ImageError);
    CHECK_THROWS_AS(wp::mse_from_halves(even, Image(1, 1), 1, 1), wp::ImageError);
}

TEST_CASE("rel_mse_from_halves by hand: the 3x3 box of the full mean as r", "[metrics]") {
    // 1x1: the box is the pixel itself. Halves of one sample each: k = 1/4, and
    // the full mean m = (2 + 1) / 2, (1 + 1) / 2, (0 + 2) / 2 = 1.5, 1, 1.
    // R: d = 1, r^2 = 2.25; G: d = 0; B: d = -2, r^2 = 1.
    const Image even = make(1, 1, {2, 1, 0}), odd = make(1, 1, {1, 1, 2});
    const double expected = (0.25 * 1.0 / 2.26 + 0.0 + 0.25 * 4.0 / 1.01) / 3.0;
    CHECK(wp::rel_mse_from_halves(even, odd, 1, 1) == Approx(expected).epsilon(1e-12));
    // Unequal halves weight the mean: 3 samples averaging 1, one sample -1:
    // m = (3 - 1) / 4 = 0.5, k = 3 / 16, d = 2.
    CHECK(wp::rel_mse_from_halves(make(1, 1, {1, 0, 0}), make(1, 1, {-1, 0, 0}), 3, 1) ==
          Approx(3.0 / 16.0 * 4.0 / 0.26 / 3.0).epsilon(1e-12));
    // 2x1: each pixel's box covers both pixels: means 1 and 2, r = 1.5 in every
    // channel; only the second pixel's halves differ (d = 2 in each channel).
    const Image e2 = make(2, 1, {1, 1, 1, 3, 3, 3}), o2 = make(2, 1, {1, 1, 1, 1, 1, 1});
    CHECK(wp::rel_mse_from_halves(e2, o2, 1, 1) ==
          Approx(3.0 * (0.25 * 4.0 / 2.26) / 6.0).epsilon(1e-12));
    CHECK_THROWS_AS(wp::rel_mse_from_halves(e2, o2, 0, 1), wp::ImageError);
}

TEST_CASE("mse_from_halves estimates the variance of the mean on synthetic samples", "[metrics]") {
    // 64x64 pixels of 8 (and 5 + 3) unit-variance Gaussian samples around a ramp:
    // the MSE of the mean is 1/8 in expectation, and so is the estimate.
    std::mt19937 rng(12345);
    std::normal_distribution<double> noise(0.0, 1.0);
    const int size = 64;
    for (int split : {4, 5}) {
        Image even(size, size), odd(size, size), mean(size, size), truth(size, size);
        for (std::size_t i = 0; i < even.rgb.size(); ++i) {
            const double r = static_cast<double>(i % 17) * 0.25;
            double se = 0.0, so = 0.0;
            for (int s = 0; s < 8; ++s)
                (s < split ? se : so) += r + noise(rng);
            even.rgb[i] = static_cast<float>(se / split);
            odd.rgb[i] = static_cast<float>(so / (8 - split));
            mean.rgb[i] = static_cast<float>((se + so) / 8.0);
            truth.rgb[i] = static_cast<float>(r);
        }
        const double estimate = wp::mse_from_halves(even, odd, static_cast<std::uint64_t>(split),
                                                    static_cast<std::uint64_t>(8 - split));
        const double actual = wp::mse(mean, truth);
        INFO("split " << split << ": estimate " << estimate << ", actual " << actual);
        // 12288 values: the estimate's relative standard error is about 1.3 %.
        CHECK(estimate == Approx(1.0 / 8.0).epsilon(0.06));
        CHECK(actual == Approx(1.0 / 8.0).epsilon(0.06));
    }
}

TEST_CASE("rel_error_map by hand, with NaN for non-finite values", "[metrics]") {
    Image map = wp::rel_error_map(image_a(), image_ref());
    // Pixel 0: 0, 1/1.01, 4/1.01; pixel 1: 0, 0.25/0.01, 1/0.01.
    const double p0 = (0.0 + 1.0 / 1.01 + 4.0 / 1.01) / 3.0, p1 = (0.0 + 25.0 + 100.0) / 3.0;
    for (int c = 0; c < 3; ++c) {
        CHECK(map.rgb[static_cast<std::size_t>(c)] == Approx(p0).epsilon(1e-6));
        CHECK(map.rgb[3 + static_cast<std::size_t>(c)] == Approx(p1).epsilon(1e-6));
    }
    // The map's mean over pixels is rel_mse.
    CHECK((p0 + p1) / 2.0 == Approx(wp::rel_mse(image_a(), image_ref())).epsilon(1e-12));
    Image broken = image_a();
    broken.rgb[1] = std::numeric_limits<float>::infinity();
    map = wp::rel_error_map(broken, image_ref());
    CHECK(std::isnan(map.rgb[0]));
    CHECK(map.rgb[3] == Approx(p1).epsilon(1e-6));
    CHECK_THROWS_AS(wp::rel_error_map(image_a(), Image(1, 1)), wp::ImageError);
    CHECK_THROWS_AS(wp::mse(image_a(), Image(2, 2)), wp::ImageError);
    CHECK_THROWS_AS(wp::mean_relative_bias(Image(), Image()), wp::ImageError);
}
