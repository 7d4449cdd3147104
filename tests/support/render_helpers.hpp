// Rendering a scene in a test, and the statistics its checks need.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "render/film.hpp"
#include "render/profiler.hpp"
#include "render/wavefront.hpp"
#include "scene/load.hpp"
#include "support/test_device.hpp"

namespace wp::test {

struct Rendered {
    Film film;
    RenderStats stats;
};

inline Rendered render(const Scene& scene, std::uint32_t spp, std::uint32_t seed = 1,
                       std::uint32_t first_sample = 0, IntegratorOptions options = {}) {
    options.seed = seed;
    WavefrontIntegrator integrator(device(), scene, options);
    Rendered out{Film(scene.camera.width, scene.camera.height), {}};
    integrator.render(first_sample, spp, out.film);
    out.stats = integrator.stats();
    return out;
}

// The reference scene at another resolution.
inline Scene hexroom(int width, int height) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/hexroom.json");
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

// The test device with OpenCL event profiling on, and a render (seed 5)
// recorded by a Profiler.
inline DeviceContext& profiling_device() {
    static DeviceContext& context = *new DeviceContext(device().info, true); // never released
    return context;
}

struct ProfiledRender {
    Profiler profiler;
    RenderStats stats;
    Film film;
};

// A max_depth below the default bounds the iterations of a wave: on the
// Oclgrind simulator (.ci/oclgrind-check) each launch costs far more than its
// work, and a path trapped between the hexroom's mirrors keeps its whole wave
// launching.
inline ProfiledRender profiled_render(const Scene& scene, std::uint32_t spp, bool regeneration,
                                      std::uint32_t pool = 0,
                                      std::uint32_t max_depth = IntegratorOptions{}.max_depth) {
    IntegratorOptions options;
    options.seed = 5;
    options.max_depth = max_depth;
    options.regeneration = regeneration;
    options.pool_size = pool;
    options.launch_plan = LaunchPlan::Stages; // the tests read the stages' records
    WavefrontIntegrator integrator(profiling_device(), scene, options);
    ProfiledRender out{{}, {}, Film(scene.camera.width, scene.camera.height)};
    integrator.set_profiler(&out.profiler);
    integrator.render(0, spp, out.film);
    out.stats = integrator.stats();
    return out;
}

// Mean over all pixels of channel c, with its standard error (from the
// per-pixel sample variances; pixels are independent).
struct MeanWithError {
    double mean = 0.0;
    double standard_error = 0.0;
};

inline MeanWithError image_mean(const Film& film, int channel) {
    Image mean = film.mean();
    Image variance = film.variance_of_mean();
    double sum = 0.0, var = 0.0;
    std::size_t pixels = static_cast<std::size_t>(film.width()) * film.height();
    for (std::size_t p = 0; p < pixels; ++p) {
        sum += mean.rgb[p * 3 + channel];
        var += variance.rgb[p * 3 + channel];
    }
    double n = static_cast<double>(pixels);
    return {sum / n, std::sqrt(var) / n};
}

// How many combined standard errors two independent estimates lie apart.
inline double sigmas_apart(const MeanWithError& a, const MeanWithError& b) {
    return std::abs(a.mean - b.mean) / std::hypot(a.standard_error, b.standard_error);
}

// Mean and standard error of channel c over the pixel rectangle [x0, x1) x [y0, y1).
inline MeanWithError region_mean(const Film& film, int channel, int x0, int y0, int x1, int y1) {
    Image mean = film.mean();
    Image variance = film.variance_of_mean();
    double sum = 0.0, var = 0.0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            std::size_t p = static_cast<std::size_t>(y) * film.width() + x;
            sum += mean.rgb[p * 3 + channel];
            var += variance.rgb[p * 3 + channel];
            ++n;
        }
    return {sum / n, std::sqrt(var) / n};
}

// Two renders of the same image compared block by block and channel by
// channel: each block mean of `a` against `b`, in units of their combined
// standard error.
struct BlockComparison {
    int blocks = 0;  // block-channel comparisons
    int outside = 0; // over `sigmas`
    double worst_sigmas = 0.0;
    double mean_sigmas = 0.0; // of |difference| / sigma
    double largest_relative_sigma = 0.0;
    std::string worst_where;
};

inline BlockComparison compare_blocks(const Film& a, const Film& b, int block,
                                      double sigmas = 5.0) {
    REQUIRE(a.width() == b.width());
    REQUIRE(a.height() == b.height());
    BlockComparison out;
    double total = 0.0;
    for (int y0 = 0; y0 + block <= a.height(); y0 += block)
        for (int x0 = 0; x0 + block <= a.width(); x0 += block)
            for (int c = 0; c < 3; ++c) {
                MeanWithError ma = region_mean(a, c, x0, y0, x0 + block, y0 + block);
                MeanWithError mb = region_mean(b, c, x0, y0, x0 + block, y0 + block);
                double sigma = std::hypot(ma.standard_error, mb.standard_error);
                double d = std::abs(ma.mean - mb.mean);
                double s = sigma > 0.0 ? d / sigma : (d == 0.0 ? 0.0 : INFINITY);
                ++out.blocks;
                total += s;
                if (s > sigmas)
                    ++out.outside;
                if (ma.mean > 0.0)
                    out.largest_relative_sigma =
                        std::max(out.largest_relative_sigma, sigma / ma.mean);
                if (s > out.worst_sigmas) {
                    out.worst_sigmas = s;
                    out.worst_where = "block (" + std::to_string(x0) + ", " + std::to_string(y0) +
                                      ") channel " + std::to_string(c) + ": " +
                                      std::to_string(ma.mean) + " vs " + std::to_string(mb.mean) +
                                      " +- " + std::to_string(sigma);
                }
            }
    out.mean_sigmas = total / std::max(1, out.blocks);
    return out;
}

} // namespace wp::test
