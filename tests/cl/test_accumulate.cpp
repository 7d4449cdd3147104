// Stage 5, accumulate: film sums over several waves against host sums, with
// non-finite samples dropped and counted.
#include "cl_test_util.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace wp::test;

TEST_CASE("accumulate: film sums over waves, dropping and counting NaN and Inf samples",
          "[cl][accumulate]") {
    const cl_uint width = 5, height = 3, pixels = width * height;
    const std::size_t slots = round_up(pixels); // every launched work-item has a slot
    const cl_uint waves = 6;

    // Slot i holds pixel permutation[i]. Slots past the frame point at pixel 0
    // with huge radiance, which would show if excess work-items accumulated.
    std::vector<cl_uint> path_pixel(slots, 0u);
    for (cl_uint i = 0; i < pixels; ++i)
        path_pixel[i] = (i * 7u + 3u) % pixels;

    std::vector<std::vector<double>> sum(pixels, std::vector<double>(4)),
        squares(pixels, std::vector<double>(4)), odd(pixels, std::vector<double>(4)),
        magnitude(pixels, std::vector<double>(4));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();

    WpFrame frame{};
    frame.width = width;
    frame.height = height;
    const cl_float4 zero = float4(0, 0, 0, 0);
    cl::Buffer pixel_buffer = upload(path_pixel);
    cl::Buffer film_sum = upload(std::vector<cl_float4>(pixels, zero));
    cl::Buffer film_squares = upload(std::vector<cl_float4>(pixels, zero));
    cl::Buffer film_odd = upload(std::vector<cl_float4>(pixels, zero));
    cl::Buffer counters = upload(std::vector<cl_uint>{11u, 22u, 33u, 0u});
    cl::Kernel kernel = wavefront_kernel("accumulate");

    std::mt19937 generator(99u);
    std::uniform_real_distribution<float> uniform(0.0f, 10.0f);
    cl_uint nonfinite = 0;
    for (cl_uint wave = 0; wave < waves; ++wave) {
        // Sample indices 3, 4, ..., 8: odd and even ones alternate.
        const cl_uint sample_index = 3 + wave;
        std::vector<cl_float4> radiance(slots, float4(1e30f, 1e30f, 1e30f, 0.0f));
        for (cl_uint slot = 0; slot < pixels; ++slot) {
            // The w component is not radiance: whatever it holds must not reach the film.
            radiance[slot] = float4(uniform(generator), uniform(generator), uniform(generator),
                                    uniform(generator));
        }
        bool dropped[64] = {};
        if (wave == 1) { // sample index 4, even
            radiance[4].s[0] = nan;
            dropped[4] = true;
        }
        if (wave == 2) { // sample index 5, odd
            radiance[7].s[1] = inf;
            dropped[7] = true;
            radiance[8].s[2] = -inf;
            dropped[8] = true;
        }
        for (cl_uint slot = 0; slot < pixels; ++slot) {
            if (dropped[slot]) {
                ++nonfinite;
                continue;
            }
            const cl_uint pixel = path_pixel[slot];
            for (int k = 0; k < 3; ++k) {
                double v = radiance[slot].s[k];
                sum[pixel][k] += v;
                squares[pixel][k] += v * v;
                magnitude[pixel][k] += std::fabs(v); // scale for the tolerance
                if (sample_index & 1u)
                    odd[pixel][k] += v;
            }
        }
        frame.sample_index = sample_index;
        cl::Buffer radiance_buffer = upload(radiance);
        set_args(kernel, frame, radiance_buffer, pixel_buffer, film_sum, film_squares, film_odd,
                 counters);
        launch(kernel, pixels);
    }

    std::vector<cl_float4> got_sum = download<cl_float4>(film_sum, pixels);
    std::vector<cl_float4> got_squares = download<cl_float4>(film_squares, pixels);
    std::vector<cl_float4> got_odd = download<cl_float4>(film_odd, pixels);
    std::vector<cl_uint> got_counters = download<cl_uint>(counters, WP_COUNTER_COUNT);

    for (cl_uint pixel = 0; pixel < pixels; ++pixel) {
        INFO("pixel " << pixel);
        for (int k = 0; k < 3; ++k) {
            INFO("channel " << k);
            // float32 sums of six non-negative terms: a few ulps of the total.
            CHECK(std::isfinite(got_sum[pixel].s[k]));
            CHECK(std::fabs(got_sum[pixel].s[k] - sum[pixel][k]) <= 1e-6 * magnitude[pixel][k]);
            CHECK(std::fabs(got_squares[pixel].s[k] - squares[pixel][k]) <=
                  1e-6 * squares[pixel][k]);
            CHECK(std::fabs(got_odd[pixel].s[k] - odd[pixel][k]) <= 1e-6 * magnitude[pixel][k]);
        }
        CHECK(got_sum[pixel].s[3] == 0.0f);
        CHECK(got_squares[pixel].s[3] == 0.0f);
        CHECK(got_odd[pixel].s[3] == 0.0f);
    }
    CHECK(nonfinite == 3);
    CHECK(got_counters[WP_COUNTER_NONFINITE] == nonfinite);
    CHECK(got_counters[WP_COUNTER_NEXT_RAYS] == 11u);
    CHECK(got_counters[WP_COUNTER_SHADOW_RAYS] == 22u);
    CHECK(got_counters[WP_COUNTER_CAPPED] == 33u);
}
