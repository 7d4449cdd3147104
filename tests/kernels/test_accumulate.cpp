// Stage 5, accumulate: film sums over many launches against host sums, with
// only the finished slots added, the sample counts kept in w, and non-finite
// samples dropped (as zero-valued samples) and counted.
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace wp;
using namespace wp::test;

TEST_CASE("accumulate: film sums and sample counts of the finished slots, dropping and counting "
          "NaN and Inf samples",
          "[cl][accumulate]") {
    const cl_uint width = 5, height = 3, pixels = width * height;
    // A pool of 6 slots: slots 0-2 own three pixels each, slots 3-5 two. Six
    // samples per pixel, numbered 3 to 8: odd and even ones alternate.
    WpFrame frame{};
    frame.width = width;
    frame.height = height;
    frame.first_sample = 3;
    frame.sample_count = 6;
    frame.pool_size = 6;
    const cl_uint pool = frame.pool_size;
    std::vector<std::vector<Task>> tasks(pool);
    for (cl_uint slot = 0; slot < pool; ++slot)
        tasks[slot] = slot_tasks(frame, slot);

    std::vector<std::vector<double>> sum(pixels, std::vector<double>(4)),
        squares(pixels, std::vector<double>(4)), odd(pixels, std::vector<double>(4)),
        magnitude(pixels, std::vector<double>(4));
    std::vector<cl_uint> count(pixels, 0u), odd_count(pixels, 0u);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();

    const cl_float4 zero = float4(0, 0, 0, 0);
    cl::Buffer film_sum = upload(std::vector<cl_float4>(pixels, zero));
    cl::Buffer film_squares = upload(std::vector<cl_float4>(pixels, zero));
    cl::Buffer film_odd = upload(std::vector<cl_float4>(pixels, zero));
    std::vector<cl_uint> initial_counters = {11u, 22u, 33u, 44u, 55u, 0u, 66u, 77u};
    REQUIRE(initial_counters.size() == WP_COUNTER_COUNT);
    cl::Buffer counters = upload(initial_counters);
    DeviceBuffers buffers = stage_buffers(pool, pixels);
    buffers.film_sum = film_sum;
    buffers.film_sum_squares = film_squares;
    buffers.film_odd_sum = film_odd;
    buffers.counters = counters;

    // Each launch finishes the current task of a random subset of the slots
    // that have tasks left, in random order, as the finished queue lists them.
    std::mt19937 generator(99u);
    std::uniform_real_distribution<float> uniform(0.0f, 10.0f);
    std::vector<std::size_t> done(pool, 0);
    cl_uint nonfinite = 0;
    bool dropped_nan_even = false, dropped_inf_odd = false, dropped_minus_inf_odd = false;
    int launches = 0;
    auto tasks_left = [&] {
        for (cl_uint slot = 0; slot < pool; ++slot)
            if (done[slot] < tasks[slot].size())
                return true;
        return false;
    };
    while (tasks_left()) {
        REQUIRE(launches < 1000);
        std::vector<cl_uint> finished, others;
        for (cl_uint slot = 0; slot < pool; ++slot) {
            const bool has_task = done[slot] < tasks[slot].size();
            (has_task && generator() % 10 < 6 ? finished : others).push_back(slot);
        }
        std::shuffle(finished.begin(), finished.end(), generator);

        // Slots not finished hold huge radiance, which would show if they
        // were added; they follow the finished ones in the queue buffer, past
        // finished_count, and point at a pixel they own.
        std::vector<cl_float4> radiance(pool, float4(1e30f, 1e30f, 1e30f, 0.0f));
        std::vector<cl_uint> path_pixel(pool), path_sample(pool);
        for (cl_uint slot = 0; slot < pool; ++slot) {
            const Task& current = tasks[slot][std::min(done[slot], tasks[slot].size() - 1)];
            path_pixel[slot] = current.pixel;
            path_sample[slot] = current.sample;
        }
        for (cl_uint slot : finished) {
            const cl_uint sample = path_sample[slot];
            // The w component is not radiance: whatever it holds must not reach the film.
            radiance[slot] = float4(uniform(generator), uniform(generator), uniform(generator),
                                    uniform(generator));
            bool dropped = false;
            if (!dropped_nan_even && launches >= 1 && sample % 2 == 0) {
                radiance[slot].s[0] = nan;
                dropped = dropped_nan_even = true;
            } else if (!dropped_inf_odd && launches >= 2 && sample % 2 == 1) {
                radiance[slot].s[1] = inf;
                dropped = dropped_inf_odd = true;
            } else if (!dropped_minus_inf_odd && launches >= 2 && sample % 2 == 1) {
                radiance[slot].s[2] = -inf;
                dropped = dropped_minus_inf_odd = true;
            }
            // A dropped sample is a zero-valued one: it counts, but adds nothing.
            const cl_uint pixel = path_pixel[slot];
            ++count[pixel];
            if (sample & 1u)
                ++odd_count[pixel];
            ++done[slot];
            if (dropped) {
                ++nonfinite;
                continue;
            }
            for (int k = 0; k < 3; ++k) {
                double v = radiance[slot].s[k];
                sum[pixel][k] += v;
                squares[pixel][k] += v * v;
                magnitude[pixel][k] += std::fabs(v); // scale for the tolerance
                if (sample & 1u)
                    odd[pixel][k] += v;
            }
        }
        std::vector<cl_uint> queue = finished;
        queue.insert(queue.end(), others.begin(), others.end());
        buffers.finished_queue = upload(queue);
        buffers.radiance = upload(radiance);
        buffers.path_pixel = upload(path_pixel);
        buffers.path_sample = upload(path_sample);
        run_stage("accumulate", frame, make_launch(cl_uint(finished.size()), 0), buffers,
                  queue.size());
        ++launches;
    }
    REQUIRE(dropped_nan_even);
    REQUIRE(dropped_inf_odd);
    REQUIRE(dropped_minus_inf_odd);

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
        // w counts samples exactly: all of them in the sum, the odd ones in
        // the odd sum (dropped ones included); the sum of squares has none.
        CHECK(count[pixel] == frame.sample_count); // the host model gave every sample once
        CHECK(odd_count[pixel] == 3u);             // samples 3, 5 and 7
        CHECK(got_sum[pixel].s[3] == float(count[pixel]));
        CHECK(got_odd[pixel].s[3] == float(odd_count[pixel]));
        CHECK(got_squares[pixel].s[3] == 0.0f);
    }
    CHECK(nonfinite == 3);
    CHECK(got_counters[WP_COUNTER_NONFINITE] == nonfinite);
    for (cl_uint i = 0; i < WP_COUNTER_COUNT; ++i) {
        INFO("counter " << i);
        if (i != WP_COUNTER_NONFINITE)
            CHECK(got_counters[i] == initial_counters[i]);
    }
}

TEST_CASE("accumulate: an empty finished queue adds nothing", "[cl][accumulate]") {
    WpFrame frame{};
    frame.width = 2;
    frame.height = 1;
    frame.sample_count = 1;
    frame.pool_size = 2;
    const cl_float4 start = float4(1.0f, 2.0f, 3.0f, 4.0f);
    cl::Buffer queue = upload(std::vector<cl_uint>{0u, 1u});
    cl::Buffer radiance = upload(std::vector<cl_float4>(2, float4(5.0f, 5.0f, 5.0f, 5.0f)));
    cl::Buffer pixel = upload(std::vector<cl_uint>{0u, 1u});
    cl::Buffer sample = upload(std::vector<cl_uint>{1u, 1u});
    cl::Buffer film_sum = upload(std::vector<cl_float4>(2, start));
    cl::Buffer film_squares = upload(std::vector<cl_float4>(2, start));
    cl::Buffer film_odd = upload(std::vector<cl_float4>(2, start));
    cl::Buffer counters = upload(std::vector<cl_uint>(WP_COUNTER_COUNT, 0u));
    DeviceBuffers buffers = stage_buffers(2, 2);
    buffers.finished_queue = queue;
    buffers.radiance = radiance;
    buffers.path_pixel = pixel;
    buffers.path_sample = sample;
    buffers.film_sum = film_sum;
    buffers.film_sum_squares = film_squares;
    buffers.film_odd_sum = film_odd;
    buffers.counters = counters;
    run_stage("accumulate", frame, make_launch(0, 0), buffers, 2);
    for (const cl::Buffer* film : {&film_sum, &film_squares, &film_odd}) {
        for (const cl_float4& v : download<cl_float4>(*film, 2))
            for (int k = 0; k < 4; ++k)
                CHECK(v.s[k] == start.s[k]);
    }
    CHECK(download<cl_uint>(counters, WP_COUNTER_COUNT) ==
          std::vector<cl_uint>(WP_COUNTER_COUNT, 0u));
}
