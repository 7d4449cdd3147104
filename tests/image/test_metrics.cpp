// Error metrics against values worked out by hand.
#include "image/metrics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using wp::Image;

namespace {

// a = (1, 2, 3), (0, 0.5, -1); ref = (1, 1, 1), (0, 0, 0).
// Differences 0, 1, 2, 0, 0.5, -1; squares 0, 1, 4, 0, 0.25, 1 (sum 6.25).
Image image_a() {
    Image img(2, 1);
    img.rgb = {1.0f, 2.0f, 3.0f, 0.0f, 0.5f, -1.0f};
    return img;
}

Image image_ref() {
    Image img(2, 1);
    img.rgb = {1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f};
    return img;
}

} // namespace

TEST_CASE("rmse and rel_mse match hand-computed values on a 2x1 image", "[metrics]") {
    CHECK(wp::rmse(image_a(), image_ref()) == Approx(std::sqrt(6.25 / 6.0)).epsilon(1e-12));
    // Denominators r^2 + 0.01: 1.01 for the first pixel, 0.01 for the second.
    const double rel = (0.0 + 1.0 / 1.01 + 4.0 / 1.01 + 0.0 + 0.25 / 0.01 + 1.0 / 0.01) / 6.0;
    CHECK(wp::rel_mse(image_a(), image_ref()) == Approx(rel).epsilon(1e-12));
    CHECK(rel == Approx(21.6584158).epsilon(1e-8)); // the same number, written out
    // Not symmetric: the reference's value sets the scale.
    CHECK(wp::rel_mse(image_ref(), image_a()) != Approx(rel));
}

TEST_CASE("metrics of an image against itself are zero", "[metrics]") {
    CHECK(wp::rmse(image_a(), image_a()) == 0.0);
    CHECK(wp::rel_mse(image_a(), image_a()) == 0.0);
}

TEST_CASE("metrics reject images of different sizes", "[metrics]") {
    const Image wide(3, 1);
    CHECK_THROWS_WITH(wp::rmse(image_a(), wide), Catch::Contains("2x1 but reference is 3x1"));
    CHECK_THROWS_AS(wp::rel_mse(wide, image_ref()), wp::ImageError);
    CHECK_THROWS_AS(wp::rmse(Image{}, Image{}), wp::ImageError); // mean of nothing
}

TEST_CASE("count_nonfinite counts NaN and infinite channel values", "[metrics]") {
    Image img = image_a();
    CHECK(wp::count_nonfinite(img) == 0);
    img.rgb[1] = std::numeric_limits<float>::quiet_NaN();
    img.rgb[3] = std::numeric_limits<float>::infinity();
    img.rgb[5] = -std::numeric_limits<float>::infinity();
    img.rgb[4] = std::numeric_limits<float>::max(); // large but finite
    CHECK(wp::count_nonfinite(img) == 3);
    CHECK(std::isnan(wp::rmse(img, image_ref())));
}
