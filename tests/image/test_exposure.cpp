// Automatic exposure: its two statistics on images whose answer is known by
// hand, the pixels it leaves out, and the invariant that makes it safe to
// use by default: the view does not depend on the image's units.
#include "image/exposure.hpp"
#include "image/tonemap.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using wp::Image;
using wp::ViewOptions;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A 1-pixel-high image of grey pixels with the given values.
Image greys(const std::vector<float>& values) {
    Image img(static_cast<int>(values.size()), 1);
    for (std::size_t i = 0; i < values.size(); ++i)
        img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = values[i];
    return img;
}

// A noisy, coloured test image with a few very bright pixels (lights).
Image random_image(unsigned seed) {
    std::mt19937 rng(seed);
    std::lognormal_distribution<float> radiance(0.0f, 1.5f);
    Image img(40, 30);
    for (float& v : img.rgb)
        v = radiance(rng);
    for (int i = 0; i < 20; ++i)
        img.pixel(i, 0)[0] = img.pixel(i, 0)[1] = img.pixel(i, 0)[2] = 1000.0f;
    return img;
}

Image scaled(Image img, float factor) {
    for (float& v : img.rgb)
        v *= factor;
    return img;
}

} // namespace

TEST_CASE("luminance uses the Rec. 709 weights", "[exposure]") {
    CHECK(wp::luminance(1, 1, 1) == Approx(1.0));
    CHECK(wp::luminance(1, 0, 0) == Approx(0.2126));
    CHECK(wp::luminance(0, 1, 0) == Approx(0.7152));
    CHECK(wp::luminance(0, 0, 1) == Approx(0.0722));
}

TEST_CASE("the median goes to mid grey unless the highlights would clip", "[exposure]") {
    // Greys 1..101: median 51 (rank 50 of 0..100), 99 % quantile 100 (rank 99).
    std::vector<float> values;
    for (int i = 1; i <= 101; ++i)
        values.push_back(static_cast<float>(i));
    const wp::AutoExposure a = wp::auto_exposure(greys(values), kInfinity);
    CHECK(a.counted == 101);
    CHECK(a.key_scale == Approx(0.18 / 51));
    CHECK(a.highlight_scale == Approx(1.0 / 100));
    CHECK(a.scale == a.key_scale); // 51 * 0.18 / 51 ... 100 * 0.18 / 51 < 1: nothing clips

    // Most pixels dark, a few percent bright: the median alone would clip the
    // bright ones, so the highlight quantile sets the exposure.
    std::vector<float> contrast(90, 0.01f);
    contrast.insert(contrast.end(), 10, 5.0f);
    const wp::AutoExposure b = wp::auto_exposure(greys(contrast), kInfinity);
    CHECK(b.key_scale == Approx(18.0));
    CHECK(b.highlight_scale == Approx(0.2));
    CHECK(b.scale == b.highlight_scale);
}

TEST_CASE("emitters, black and non-finite pixels are not counted", "[exposure]") {
    std::vector<float> values;
    for (int i = 1; i <= 101; ++i)
        values.push_back(static_cast<float>(i));
    const wp::AutoExposure plain = wp::auto_exposure(greys(values), kInfinity);
    // Lights at 1000 (threshold 500), black pixels and a NaN and an infinity.
    values.insert(values.end(), {1000.0f, 1000.0f, 700.0f, 0.0f, 0.0f, -1.0f,
                                 std::numeric_limits<float>::quiet_NaN(),
                                 std::numeric_limits<float>::infinity()});
    const wp::AutoExposure with_extras = wp::auto_exposure(greys(values), 500.0);
    CHECK(with_extras.counted == 101);
    CHECK(with_extras.emitters == 3);
    CHECK(with_extras.scale == plain.scale);
    // Without the threshold the lights count, and the highlight moves.
    CHECK(wp::auto_exposure(greys(values), kInfinity).counted == 104);

    // Nothing to count: the scale stays 1.
    CHECK(wp::auto_exposure(greys({0.0f, 0.0f}), kInfinity).scale == 1.0);
    CHECK(wp::auto_exposure(greys({900.0f}), 500.0).scale == 1.0);
    CHECK(wp::auto_exposure(Image{}, kInfinity).scale == 1.0);
}

TEST_CASE("scaling the radiance by 2^k leaves the automatic view unchanged", "[exposure]") {
    const Image img = random_image(7);
    for (const wp::ToneMap tonemap : {wp::ToneMap::Srgb, wp::ToneMap::Filmic}) {
        ViewOptions view;
        view.tonemap = tonemap;
        view.emitter_luminance = 500.0;
        view.exposure_stops = 0.5;
        const std::vector<std::uint8_t> reference = wp::to_rgb8(img, view);
        for (const int k : {-30, -10, -1, 1, 7, 20}) {
            INFO("tone map " << wp::to_string(tonemap) << ", k = " << k);
            const auto factor = static_cast<float>(std::ldexp(1.0, k));
            ViewOptions scaled_view = view;
            scaled_view.emitter_luminance = view.emitter_luminance * factor;
            const Image brighter = scaled(img, factor);
            CHECK(wp::to_rgb8(brighter, scaled_view) == reference);
            // A fixed exposure does not adapt: the same scaling changes the view.
            const ViewOptions fixed = ViewOptions::fixed(0.0, tonemap);
            CHECK(wp::to_rgb8(brighter, fixed) != wp::to_rgb8(img, fixed));
        }
    }
}

TEST_CASE("the exposure offset is in stops from the automatic exposure", "[exposure]") {
    const Image img = random_image(3);
    ViewOptions view;
    const double automatic = wp::exposure_scale(img, view);
    CHECK(automatic == wp::auto_exposure(img, kInfinity).scale);
    view.exposure_stops = 1.0;
    CHECK(wp::exposure_scale(img, view) == 2.0 * automatic);
    view.exposure_stops = -2.5;
    CHECK(wp::exposure_scale(img, view) == Approx(automatic * std::exp2(-2.5)));
    CHECK(wp::exposure_scale(img, ViewOptions::fixed(-2.5)) == std::exp2(-2.5));
    // The view says what it did, in numbers --fixed-exposure takes back.
    CHECK(wp::describe_view(img, ViewOptions::fixed(-2.5)) == "srgb, exposure -2.5 stops (fixed)");
    const std::string text = wp::describe_view(img, view);
    CHECK(text.find("srgb, exposure ") == 0);
    CHECK(text.find("offset -2.5)") != std::string::npos);
}

TEST_CASE("isolated fireflies do not set the exposure; bright regions do", "[exposure]") {
    // Grey 0.5 with a firefly of 100 at every 5th pixel of every 5th row and
    // column offset (4 % of the pixels, none next to another).
    Image img(50, 50);
    std::fill(img.rgb.begin(), img.rgb.end(), 0.5f);
    for (int y = 0; y < 50; y += 5)
        for (int x = (y / 5) % 5; x < 50; x += 5)
            img.pixel(x, y)[0] = img.pixel(x, y)[1] = img.pixel(x, y)[2] = 100.0f;
    const wp::AutoExposure noisy = wp::auto_exposure(img, kInfinity);
    CHECK(noisy.highlight_scale == Approx(1.0 / 0.5));
    CHECK(noisy.scale == Approx(0.18 / 0.5));
    // A bright block 3 pixels high (6 % of the image) is light, not noise:
    // it keeps the exposure from clipping it.
    for (int y = 20; y < 23; ++y)
        for (int x = 0; x < 50; ++x)
            img.pixel(x, y)[0] = img.pixel(x, y)[1] = img.pixel(x, y)[2] = 10.0f;
    const wp::AutoExposure lit = wp::auto_exposure(img, kInfinity);
    CHECK(lit.highlight_scale == Approx(1.0 / 10.0));
    CHECK(lit.scale == lit.highlight_scale);
}
