// Rendering a scene in a test, and the statistics its checks need.
#pragma once

#include <cmath>

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

inline ProfiledRender profiled_render(const Scene& scene, std::uint32_t spp, bool regeneration,
                                      std::uint32_t pool = 0) {
    IntegratorOptions options;
    options.seed = 5;
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

// The mean of the w x w block (bx, by) of a film's channel, with its
// standard error.
inline MeanWithError block_mean(const Film& film, int bx, int by, int w, int channel) {
    Image mean = film.mean();
    Image variance = film.variance_of_mean();
    double sum = 0.0, var = 0.0;
    for (int y = by * w; y < (by + 1) * w; ++y)
        for (int x = bx * w; x < (bx + 1) * w; ++x) {
            std::size_t p = static_cast<std::size_t>(y) * film.width() + x;
            sum += mean.rgb[p * 3 + channel];
            var += variance.rgb[p * 3 + channel];
        }
    double n = static_cast<double>(w) * w;
    return {sum / n, std::sqrt(var) / n};
}

// How many combined standard errors two independent estimates lie apart.
inline double sigmas_apart(const MeanWithError& a, const MeanWithError& b) {
    return std::abs(a.mean - b.mean) / std::hypot(a.standard_error, b.standard_error);
}

} // namespace wp::test
