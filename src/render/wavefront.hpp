// The wavefront path tracer on one OpenCL device.
//
// A wave computes one sample for every pixel: `generate` fills one path slot
// per pixel and queues its camera ray; then, bounce after bounce, `intersect`
// finds the closest hits of the queued rays, `shade` adds emission, queues one
// shadow ray per diffuse hit and pushes surviving paths to the next queue, and
// `shadow` adds the unblocked light. When the queue is empty, `accumulate`
// adds the wave's radiance to the film. See docs/architecture.md.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cl/context.hpp"
#include "cl/program.hpp"
#include "render/device_scene.hpp"
#include "render/film.hpp"
#include "scene/scene.hpp"

namespace wp {

struct IntegratorOptions {
    std::uint32_t seed = 0;
    // Safety cap on bounces. Russian roulette ends paths long before it in
    // any scene with absorption; it exists for lossless mirror corridors. The
    // number of paths it cuts is counted in RenderStats::capped_paths.
    std::uint32_t max_depth = 1024;
    bool general_kernels = false; // compile every feature, not just the scene's
    // Next-event estimation: one shadow ray to a light per diffuse hit. Off,
    // light is found only by paths that hit emitters.
    bool next_event_estimation = true;
};

struct RenderStats {
    std::uint64_t camera_rays = 0;
    std::uint64_t bounce_rays = 0; // rays after the first hit
    std::uint64_t shadow_rays = 0;
    std::uint64_t capped_paths = 0;
    std::uint64_t nonfinite_samples = 0;
    std::vector<std::uint64_t> rays_per_depth; // queue length at each bounce, summed over waves
    double render_seconds = 0.0;               // wall time of render() calls
};

class WavefrontIntegrator {
  public:
    WavefrontIntegrator(DeviceContext& device, const Scene& scene, IntegratorOptions options);

    // Renders samples [first_sample, first_sample + count) of every pixel into
    // the film; `on_wave(done)` is called after each wave.
    void render(std::uint32_t first_sample, std::uint32_t count, Film& film,
                const std::function<void(std::uint32_t)>& on_wave = {});

    const RenderStats& stats() const { return stats_; }
    const BuiltProgram& program() const { return program_; }
    const SceneFeatures& features() const { return features_; }
    int width() const { return scene_.width; }
    int height() const { return scene_.height; }

  private:
    void run_wave(std::uint32_t sample_index);
    void flush_film(Film& film, std::uint64_t samples, std::uint64_t odd);
    void launch(cl::Kernel& kernel, std::uint32_t items);

    DeviceContext& device_;
    DeviceScene scene_;
    SceneFeatures features_;
    IntegratorOptions options_;
    BuiltProgram program_;
    WpFrame frame_{};
    std::uint32_t pixel_count_ = 0;

    cl::Kernel generate_, intersect_, shade_, shadow_, accumulate_;

    // Scene.
    cl::Buffer triangles_, spheres_, materials_, lights_;
    // Path state, one entry per slot (structure of arrays).
    cl::Buffer ray_origin_, ray_direction_, throughput_, radiance_;
    cl::Buffer path_pixel_, path_depth_, path_flags_, hit_t_, hit_primitive_;
    cl::Buffer shadow_origin_, shadow_direction_, shadow_contribution_;
    // Queues of slot indices, and the counters the kernels push with.
    cl::Buffer queue_a_, queue_b_, shadow_queue_, counters_;
    // Film for the current batch of waves (float4 per pixel).
    cl::Buffer film_sum_, film_sum_squares_, film_odd_sum_;

    RenderStats stats_;
};

} // namespace wp
