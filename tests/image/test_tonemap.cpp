// View transforms: sRGB at known points, exposure, the Seed view, and non-finite input.
#include "image/tonemap.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using wp::Image;
using wp::ToneMap;
using wp::ViewOptions;

namespace {

// Independent reference: the IEC 61966-2-1 formula, rounded to nearest.
int expected_srgb_byte(double linear) {
    const double c = std::min(std::max(linear, 0.0), 1.0);
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::floor(s * 255.0 + 0.5));
}

// Tone maps a single gray pixel and returns its red byte.
int srgb_byte(float value, double exposure = 0.0) {
    Image img(1, 1);
    img.rgb = {value, value, value};
    return wp::to_rgb8(img, ViewOptions::fixed(exposure))[0];
}

} // namespace

TEST_CASE("sRGB view at known points", "[tonemap]") {
    CHECK(srgb_byte(0.0f) == 0);
    CHECK(srgb_byte(1.0f) == 255);
    CHECK(srgb_byte(0.5f) == 188); // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5
    CHECK(srgb_byte(7.0f) == 255); // clamped
    CHECK(srgb_byte(-1.0f) == 0);  // clamped
    // Both sides of the linear/power boundary, against the formula.
    CHECK(srgb_byte(0.0031308f) == 10); // 12.92 * 0.0031308 * 255 = 10.31
    CHECK(srgb_byte(0.0031308f) == expected_srgb_byte(0.0031308f));
    CHECK(srgb_byte(0.003f) == expected_srgb_byte(0.003f));
    CHECK(srgb_byte(0.0032f) == expected_srgb_byte(0.0032f));
    CHECK(srgb_byte(0.001f) == 3); // 12.92 * 0.001 * 255 = 3.29
    for (int i = 0; i <= 1000; ++i) {
        const float v = static_cast<float>(i) / 1000.0f;
        INFO("linear value " << v);
        CHECK(srgb_byte(v) == expected_srgb_byte(v));
    }
}

TEST_CASE("exposure +1 doubles the linear input, -1 halves it", "[tonemap]") {
    CHECK(srgb_byte(0.25f, 1.0) == srgb_byte(0.5f));
    CHECK(srgb_byte(0.25f, 1.0) == 188);
    CHECK(srgb_byte(1.0f, -1.0) == 188);
    CHECK(srgb_byte(0.1f, 2.0) == expected_srgb_byte(0.4));
    CHECK(srgb_byte(0.6f, 1.0) == 255); // 1.2 clamps
}

TEST_CASE("sRGB view keeps pixel order and channel order", "[tonemap]") {
    Image img(2, 1);
    img.rgb = {1.0f, 0.0f, 0.5f, 0.0f, 0.5f, 1.0f};
    CHECK(wp::to_rgb8(img, ViewOptions::fixed(0.0)) ==
          std::vector<std::uint8_t>{255, 0, 188, 0, 188, 255});
}

TEST_CASE("non-finite values map to 0 in the sRGB view", "[tonemap]") {
    Image img(2, 1);
    const float inf = std::numeric_limits<float>::infinity();
    img.rgb = {std::numeric_limits<float>::quiet_NaN(), inf, -inf, 1.0f, 0.0f, 0.5f};
    CHECK(wp::to_rgb8(img, ViewOptions::fixed(0.0)) ==
          std::vector<std::uint8_t>{0, 0, 0, 255, 0, 188});
    // A huge exposure makes 0 * 2^e = 0 * inf = NaN internally; still defined.
    CHECK(wp::to_rgb8(img, ViewOptions::fixed(5000.0)) ==
          std::vector<std::uint8_t>{0, 0, 0, 255, 0, 255});
    CHECK_THROWS_AS(wp::to_rgb8(img, ViewOptions::fixed(std::nan(""))), wp::ImageError);
}

TEST_CASE("Seed view on a hand-made 2x1 image", "[tonemap]") {
    Image img(2, 1);
    img.rgb = {4.0f, 1.0f, 0.0f, 0.25f, 16.0f, 9.0f};
    // sqrt: 2, 1, 0, 0.5, 4, 3; max 4. Times 255.99 / 4, truncated:
    // 127.995, 63.9975, 0, 31.99875, 255.99, 191.9925.
    const std::vector<std::uint8_t> expected = {127, 63, 0, 31, 255, 191};
    CHECK(wp::to_rgb8(img, ViewOptions::fixed(0.0, ToneMap::Seed)) == expected);
    // The view normalises by the maximum, so exposure cannot change it.
    CHECK(wp::to_rgb8(img, ViewOptions::fixed(3.0, ToneMap::Seed)) == expected);
}

TEST_CASE("Seed view: all-zero image, non-finite and negative values give 0", "[tonemap]") {
    Image black(2, 2);
    CHECK(wp::to_rgb8(black, ViewOptions::fixed(0.0, ToneMap::Seed)) ==
          std::vector<std::uint8_t>(12, 0));

    Image img(2, 1);
    const float inf = std::numeric_limits<float>::infinity();
    img.rgb = {std::numeric_limits<float>::quiet_NaN(), inf, -1.0f, 1.0f, 0.25f, 0.0f};
    // Only 1 and 0.25 count: sqrt 1 and 0.5 -> 255.99 and 127.995.
    CHECK(wp::to_rgb8(img, ViewOptions::fixed(0.0, ToneMap::Seed)) ==
          std::vector<std::uint8_t>{0, 0, 0, 255, 127, 0});
}

TEST_CASE("to_rgb8 rejects a mis-sized image", "[tonemap]") {
    Image img(2, 2);
    img.rgb.resize(5);
    CHECK_THROWS_AS(wp::to_rgb8(img, ViewOptions::fixed(0.0)), wp::ImageError);
    CHECK(wp::to_rgb8(Image{}, ViewOptions{}).empty());
}

namespace {

// The filmic bytes of one pixel at a fixed exposure of 0.
std::vector<std::uint8_t> filmic(float r, float g, float b) {
    Image img(1, 1);
    img.rgb = {r, g, b};
    return wp::to_rgb8(img, ViewOptions::fixed(0.0, ToneMap::Filmic));
}

} // namespace

TEST_CASE("filmic view: neutral, monotonic, rolls highlights off", "[tonemap]") {
    CHECK(filmic(0, 0, 0) == std::vector<std::uint8_t>{0, 0, 0});
    // ACES puts 18 % grey at about 10 % display luminance: Hill's fit gives
    // (0.18 * (0.18 + 0.0245786) - 0.000090537) / (0.18 * (0.983729 * 0.18 +
    // 0.4329510) + 0.238081) = 0.10559 (its matrices' rows sum to 1, so grey
    // stays grey), which the sRGB curve shows as about 92.
    const std::vector<std::uint8_t> mid = filmic(0.18f, 0.18f, 0.18f);
    CHECK(std::abs(int(mid[0]) - expected_srgb_byte(0.10559)) <= 1);
    int previous = 0;
    for (int i = 0; i <= 400; ++i) {
        const float v = std::exp2(static_cast<float>(i - 200) / 20.0f); // 2^-10 .. 2^10
        const std::vector<std::uint8_t> bytes = filmic(v, v, v);
        INFO("grey " << v);
        CHECK(std::abs(int(bytes[0]) - int(bytes[1])) <= 1); // neutral in, neutral out
        CHECK(std::abs(int(bytes[2]) - int(bytes[1])) <= 1);
        CHECK(int(bytes[1]) >= previous);
        previous = bytes[1];
    }
    // Where sRGB clips (1, 2 and 4 all show 255), filmic still tells them apart,
    // and reaches white only near 25.7.
    CHECK(filmic(1, 1, 1)[1] < filmic(2, 2, 2)[1]);
    CHECK(filmic(2, 2, 2)[1] < filmic(4, 4, 4)[1]);
    CHECK(filmic(4, 4, 4)[1] < 255);
    CHECK(filmic(30, 30, 30) == std::vector<std::uint8_t>{255, 255, 255});
    // A very bright red turns towards white rather than staying pure red.
    const std::vector<std::uint8_t> red = filmic(200, 0, 0);
    CHECK(red[0] == 255);
    CHECK(red[1] > 100);
    CHECK(red[2] > 100);
    // Non-finite and negative values are black, as in the sRGB view.
    CHECK(filmic(std::nanf(""), -1.0f, std::numeric_limits<float>::infinity()) ==
          std::vector<std::uint8_t>{0, 0, 0});
}
