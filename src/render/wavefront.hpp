// The wavefront path tracer on one OpenCL device.
//
// A pool of path slots (one per pixel by default) is driven through the five
// stages: `generate` gives slots camera rays; then, iteration after iteration,
// `intersect` finds the closest hits of the queued rays, `shade` adds
// emission, queues one shadow ray per diffuse hit and sorts paths into the
// next ray queue or the finished queue, `shadow` adds the unblocked light,
// `accumulate` adds finished paths to the film, and (with regeneration)
// `generate` refills the finished slots with their next samples, so the queue
// stays full while long paths drain. See docs/architecture.md.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cl/context.hpp"
#include "cl/program.hpp"
#include "render/device_buffers.hpp"
#include "render/device_scene.hpp"
#include "render/film.hpp"
#include "render/integrator_options.hpp"
#include "render/prepared_scene.hpp"
#include "render/profiler.hpp"
#include "render/self_check.hpp"
#include "scene/scene.hpp"

namespace wp {

struct RenderStats {
    std::uint64_t camera_rays = 0;
    std::uint64_t bounce_rays = 0; // rays after the first hit
    std::uint64_t shadow_rays = 0;
    std::uint64_t iterations = 0; // intersect/shade launches
    std::uint64_t capped_paths = 0;
    std::uint64_t nonfinite_samples = 0;
    std::vector<std::uint32_t> queue_lengths; // rays traced in each iteration
    // Without regeneration: rays traced at each bounce of a wave, summed over
    // waves (how the queue drains). Empty with regeneration, where an
    // iteration mixes bounces.
    std::vector<std::uint64_t> rays_per_bounce;
    double render_seconds = 0.0; // wall time of render() calls
    double host_seconds = 0.0;   // host work inside it (folding the film)
};

// How the integrator launches its work on one device: the launch plan
// `requested` resolves to for a program whose tracing is (or is not) the
// fixed-count kind that PoCL vectorises across a work-group
// (SceneFeatures::fixed_counts without a hierarchy), regeneration, and how
// often the device's float32 film is folded into the host's. Auto: by
// device type and that, from the measurements of docs/performance.md,
// "Launch plans (fusion), measured", and docs/gpu.md, "The launch plan of a
// GPU". And why, in one line for `wavepath info`.
struct ChosenLaunchPlan {
    LaunchPlan plan = LaunchPlan::Stages;
    std::string why;
    bool regeneration = false;
    std::string regeneration_why;
    // Whether shade takes its rays sorted by material (--shade-order, the
    // stages plan only), and why.
    bool sorted_shading = false;
    std::string shade_order_why;
    // Iterations of the stages plans between folds of the film; samples per
    // render call the CLI asks for (the wave plan folds per call).
    std::uint32_t iterations_per_flush = 32;
    std::uint32_t samples_per_call = 1;
};
// Throws std::runtime_error for --shade-order sorted with a fused plan.
ChosenLaunchPlan choose_launch_plan(LaunchPlan requested, const DeviceInfo& device,
                                    bool vectorised_tracing,
                                    std::optional<bool> regeneration = std::nullopt,
                                    ShadeOrder shade_order = ShadeOrder::Auto);

// The stages and bounce plans hand a wave's last paths to the tail kernel
// (kernels/tail.cl) once at most this many rays are left: on the two-core
// PoCL machine the tail kernel, which runs scalar, costs about 5x the
// vectorised stages per ray, and a stage iteration of a few rays about
// 0.4 ms of launches and sync (docs/performance.md, "A wave's tail in one
// launch").
inline constexpr std::uint32_t kDefaultTailRays = 512;
// No tail by default below this pool (a 64x64 image): so small a render
// saves less on its tail's launches than the tail kernel's first build costs
// (PoCL compiles a kernel at its first launch, once per set of build
// options; the test suite's small renders took 130 s longer cold with it).
inline constexpr std::uint32_t kTailMinimumPool = 4096;
// The threshold a render uses: WAVEPATH_TAIL_RAYS if set (for measuring),
// else IntegratorOptions::tail_rays if set, else kDefaultTailRays but at
// most a sixteenth of the pool, so that a small pool still runs its first
// bounces through the stage kernels, and 0 below kTailMinimumPool. 0: never.
std::uint32_t tail_rays_for(std::optional<std::uint32_t> option, std::uint32_t pool_size);

// The features the integrator gives `scene` under `options` (analyse_features,
// then the traversal and shadow culling asked for), and those its kernels are
// compiled for: these, or every feature with --general.
SceneFeatures integrator_features(const Scene& scene, const IntegratorOptions& options);
SceneFeatures compiled_features(const SceneFeatures& features, const IntegratorOptions& options);

// The -D options that compile the kernels for `features` and the estimator
// of `options` (the one place that makes them).
std::string kernel_build_options(const SceneFeatures& features, const IntegratorOptions& options);

class WavefrontIntegrator {
  public:
    // Builds the kernels for `scene` on `device` and uploads its arrays, in
    // place where the device shares the host's memory: then its buffers hold
    // the arrays until they are deleted (render/prepared_scene.hpp).
    WavefrontIntegrator(DeviceContext& device, const PreparedScene& scene);
    // The same for a scene prepared for this device alone.
    WavefrontIntegrator(DeviceContext& device, const Scene& scene, IntegratorOptions options);

    // Renders samples [first_sample, first_sample + count) of every pixel into
    // the film; `on_progress(samples_per_pixel_done)` is called as they finish.
    void render(std::uint32_t first_sample, std::uint32_t count, Film& film,
                const std::function<void(double)>& on_progress = {});

    // The most samples per pixel one pass over the pool may hold: a slot's
    // 32-bit task counter must not wrap (render() splits larger requests).
    static std::uint32_t max_samples_per_call(std::uint64_t pixels, std::uint64_t pool);

    // Records every launch in `profiler` (nullptr: off). The device's queue
    // must have been created with profiling enabled.
    void set_profiler(Profiler* profiler) { profiler_ = profiler; }

    const RenderStats& stats() const { return stats_; }
    const BuiltProgram& program() const { return program_; }
    const SceneFeatures& features() const { return features_; }
    const IntegratorOptions& options() const { return options_; }
    // The plan the render runs (never Auto) and why it was chosen.
    const ChosenLaunchPlan& launch_plan() const { return plan_; }
    // "stages, regeneration, pool 640000, work-groups of 64": the plan as
    // `wavepath info` and the image metadata give it.
    std::string launch_summary() const;
    std::size_t work_group_size() const { return group_size_; }
    // The live rays from which the tail kernel finishes a wave (0: never;
    // tail_rays_for).
    std::uint32_t tail_rays() const { return tail_rays_; }
    // The self-check's verdict, if one was asked for and applied: the
    // specialised and general options differ (render/self_check.hpp).
    const std::optional<SelfCheckVerdict>& self_check() const { return self_check_; }
    std::uint32_t pool_size() const { return pool_size_; }
    DeviceContext& device() const { return device_; }
    int width() const { return static_cast<int>(frame_.width); }
    int height() const { return static_cast<int>(frame_.height); }

    // For stage benchmarks: traces `rays` (origin xyz, direction xyz, packed
    // as float4 pairs) through intersect alone, `repetitions` times; returns
    // the device seconds of the intersect launches (profiling must be on).
    double time_intersect(const std::vector<cl_float4>& origins,
                          const std::vector<cl_float4>& directions, int repetitions);
    // Same for shadow rays: direction w is the segment length.
    double time_shadow(const std::vector<cl_float4>& origins,
                       const std::vector<cl_float4>& directions, int repetitions);

  private:
    // One call's samples: resets the slots and counters, traces them by the
    // launch plan, folds the film and reads the final counters.
    void render_range(std::uint32_t first_sample, std::uint32_t count, Film& film,
                      const std::function<void(double)>& on_progress);
    // The stages and bounce plans: a launch per stage (or one fused launch)
    // and one sync per bounce, until every slot has finished its samples.
    void trace_bounces(Film& film, const std::function<void(double)>& on_progress);
    // Sorts ray queue `queue` (at most `bound` rays) by material into
    // shade_order (kernels/shade_sort.cl): zeroes the counts, two launches.
    void sort_for_shade(cl_uint queue, std::uint32_t bound);
    // The wave plan: megakernel launches of `count` samples' tasks, no
    // per-bounce sync.
    void trace_waves(std::uint32_t count, Film& film,
                     const std::function<void(double)>& on_progress);
    // Launches `stage` over `items` work-items (rounded up to whole groups).
    // `other`: a kernel that is not the stage's, profiled as the stage.
    void launch(Stage stage, const WpLaunch& arguments, std::uint32_t items,
                cl::Kernel* other = nullptr);
    // Device seconds of `repetitions` launches of one stage.
    double time_launches(Stage stage, const WpLaunch& arguments, std::uint32_t items,
                         int repetitions);
    void load_rays(const cl::Buffer& origin_buffer, const cl::Buffer& direction_buffer,
                   const cl::Buffer& queue, const std::vector<cl_float4>& origins,
                   const std::vector<cl_float4>& directions);
    void read(const cl::Buffer& buffer, std::size_t bytes, void* out, bool blocking);
    void flush_film(Film& film);
    void clear_film();

    DeviceContext& device_;
    SceneFeatures features_;
    IntegratorOptions options_;
    ChosenLaunchPlan plan_;
    std::optional<SelfCheckVerdict> self_check_;
    std::size_t group_size_ = 0; // work-group size of every launch
    BuiltProgram program_;
    WpFrame frame_{};
    std::uint32_t pixel_count_ = 0;
    std::uint32_t pool_size_ = 0;
    std::uint32_t tail_rays_ = 0; // tail_rays()
    // Kernels built with WP_MIRROR_NEE: the mirror queue's two-leg shadow rays
    // go to mirror_shadow (kernels/shadow.cl) after the shadow stage.
    bool mirror_shadows_ = false;
    cl::Kernel mirror_shadow_kernel_;
    cl::Kernel shade_sort_count_kernel_; // the sort's first launch (with sorted_shading)
    Profiler* profiler_ = nullptr;

    std::array<cl::Kernel, kStageKernelNames.size()> kernels_; // by Stage
    DeviceBuffers buffers_;

    RenderStats stats_;
};

} // namespace wp
