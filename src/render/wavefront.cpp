#include "render/wavefront.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace wp {
namespace {

// Launches use work-groups of this size (or the device's maximum, if smaller)
// and round the item count up to a multiple; kernels ignore the excess items
// and never depend on the group size. A fixed size matters on PoCL, which
// compiles a kernel anew for every distinct local size it is given.
constexpr std::uint32_t kWorkGroupSize = 64;

// The wave plan: with regeneration a megakernel launch runs this many tasks
// of each slot back to back (without, one: each launch is one wave); the
// film is folded after this many tasks per slot, about as often as the
// stages plan folds it on a CPU (ChosenLaunchPlan::iterations_per_flush).
constexpr std::uint32_t kWaveTasksPerFlush = 8;

// The work-group size: kWorkGroupSize, or WAVEPATH_WORK_GROUP_SIZE (for
// measuring; docs/performance.md), at most the device's maximum and
// WP_MAX_WORK_GROUP_SIZE (shade's compaction arrays, kernels/shade.cl).
std::size_t work_group_size_for(const DeviceInfo& device) {
    std::size_t size = kWorkGroupSize;
    if (const char* text = std::getenv("WAVEPATH_WORK_GROUP_SIZE"))
        if (const long value = std::strtol(text, nullptr, 10); value > 0)
            size = static_cast<std::size_t>(value);
    return std::min({size, device.max_work_group_size, std::size_t{WP_MAX_WORK_GROUP_SIZE}});
}

std::string gibibytes(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f GiB", static_cast<double>(bytes) / (1ull << 30));
    return text;
}

// Fails with a clear message before allocating what the device cannot hold
// (drivers report this late and vaguely, if at all).
void check_device_memory(const DeviceInfo& device, int width, int height, std::uint64_t slots,
                         bool aovs) {
    const std::uint64_t pixels =
        static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    const PathBufferBytes bytes = path_buffer_bytes(aovs);
    const std::uint64_t total = bytes.total(slots, pixels);
    const char* largest_name = "";
    const std::uint64_t largest = bytes.largest(slots, pixels, &largest_name);
    const std::uint64_t max_alloc = device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    if (total > device.global_memory_bytes || largest > max_alloc)
        throw std::runtime_error("out of device memory: a " + std::to_string(width) + "x" +
                                 std::to_string(height) + " image needs " + gibibytes(total) +
                                 " (largest buffer " + largest_name + ", " + gibibytes(largest) +
                                 ") on " + device.name + ", which has " +
                                 gibibytes(device.global_memory_bytes) + " (largest buffer " +
                                 gibibytes(max_alloc) + "); use a smaller --width/--height");
}

// The same for the scene's buffers (geometry, hierarchy, textures), once
// they are flattened and before any is uploaded.
void check_scene_memory(const DeviceInfo& device, const DeviceScene& scene) {
    std::uint64_t total = 0, largest = 0;
    const char* largest_name = "";
#define WP_SCENE_BUFFER_BYTES(name, type)                                                          \
    {                                                                                              \
        const std::uint64_t bytes = scene.name.size() * sizeof(type);                              \
        total += bytes;                                                                            \
        if (bytes > largest) {                                                                     \
            largest = bytes;                                                                       \
            largest_name = #name;                                                                  \
        }                                                                                          \
    }
    WP_SCENE_BUFFERS(WP_SCENE_BUFFER_BYTES)
#undef WP_SCENE_BUFFER_BYTES
    const std::uint64_t max_alloc = device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    if (total > device.global_memory_bytes || largest > max_alloc)
        throw std::runtime_error("out of device memory: the scene needs " + gibibytes(total) +
                                 " (largest buffer " + largest_name + ", " + gibibytes(largest) +
                                 ") on " + device.name + ", which has " +
                                 gibibytes(device.global_memory_bytes) + " (largest buffer " +
                                 gibibytes(max_alloc) + ")");
}

} // namespace

std::uint32_t tail_rays_for(std::optional<std::uint32_t> option, std::uint32_t pool_size) {
    if (const char* text = std::getenv("WAVEPATH_TAIL_RAYS")) {
        char* end = nullptr;
        const unsigned long value = std::strtoul(text, &end, 10);
        if (end == text || *end != '\0' || text[0] == '-' || value > UINT32_MAX)
            throw std::runtime_error(std::string("WAVEPATH_TAIL_RAYS is '") + text +
                                     "', not a number of rays (0: no tail kernel)");
        return static_cast<std::uint32_t>(value);
    }
    if (option)
        return *option;
    if (pool_size < kTailMinimumPool)
        return 0;
    return std::min(kDefaultTailRays, pool_size / 16u);
}

ChosenLaunchPlan choose_launch_plan(LaunchPlan requested, const DeviceInfo& device,
                                    bool vectorised_tracing, std::optional<bool> regeneration,
                                    ShadeOrder shade_order) {
    const bool cpu = device.type == "CPU";
    const bool sorted = shade_order == ShadeOrder::Sorted;
    if (sorted && requested != LaunchPlan::Auto && requested != LaunchPlan::Stages)
        throw std::runtime_error("--shade-order sorted needs the stages launch plan, not "
                                 "--launch-plan " +
                                 to_string(requested));
    ChosenLaunchPlan chosen;
    if (requested != LaunchPlan::Auto) {
        chosen.plan = requested;
        chosen.why = "asked for (--launch-plan " + to_string(requested) + ")";
    } else if (sorted) {
        chosen.plan = LaunchPlan::Stages;
        chosen.why = "auto: --shade-order sorted, which only the stages plan runs";
    } else if (!cpu) {
        chosen.plan = LaunchPlan::Stages;
        chosen.why = "auto: a " + (device.type.empty() ? std::string("non-CPU") : device.type) +
                     " device: separate stage kernels (on the H200: 1.1x the bounce plan's "
                     "samples/s, 1.4x the wave plan's; docs/gpu.md, \"The launch plan of a GPU\")";
    } else if (vectorised_tracing) {
        chosen.plan = LaunchPlan::Stages;
        chosen.why = "auto: a CPU device and fixed-count tracing, which PoCL vectorises across a "
                     "work-group only in the separate intersect and shadow kernels (fused, it "
                     "runs scalar: 2.4x slower; docs/performance.md, \"Launch plans (fusion), "
                     "measured\")";
    } else {
        chosen.plan = LaunchPlan::Wave;
        chosen.why = "auto: a CPU device and hierarchy or general tracing, which no plan "
                     "vectorises: the wave megakernel saves the stages' memory traffic and host "
                     "round trips (docs/performance.md, \"Launch plans (fusion), measured\")";
    }
    if (regeneration) {
        chosen.regeneration = *regeneration;
        chosen.regeneration_why =
            *regeneration ? "asked for (--regeneration)" : "asked for (--no-regeneration)";
    } else if (cpu) {
        chosen.regeneration = false;
        chosen.regeneration_why = "auto: off on a CPU device (30-40 % slower with it on PoCL, "
                                  "docs/profiling.md)";
    } else {
        chosen.regeneration = true;
        chosen.regeneration_why = "auto: on for a GPU, whose launches it keeps full (3.5x the "
                                  "samples/s on the H200, docs/gpu.md)";
    }
    if (chosen.plan != LaunchPlan::Stages) {
        chosen.sorted_shading = false;
        chosen.shade_order_why = "arrival: the " + to_string(chosen.plan) +
                                 " plan shades each ray in the work-item that traced it";
    } else if (shade_order != ShadeOrder::Auto) {
        chosen.sorted_shading = sorted;
        chosen.shade_order_why = "asked for (--shade-order " + to_string(shade_order) + ")";
    } else {
        // PoCL runs shade scalar, so a sorted queue buys no SIMD coherence and
        // costs the sort; on a GPU, where warps would gain, it is unmeasured.
        chosen.sorted_shading = false;
        chosen.shade_order_why =
            cpu ? "auto: arrival on a CPU device (sorted measured slower on PoCL, which runs "
                  "shade scalar: no gain in shade on the showcase, a loss on the hexroom, plus "
                  "the sort; docs/performance.md, \"Shading sorted by material\")"
                : "auto: arrival (sorted is not yet measured on a GPU; docs/performance.md, "
                  "\"Shading sorted by material\")";
    }
    // The film: on a CPU device a fold costs about what the iterations
    // between folds do; a GPU runs 32 iterations in a fraction of the fold's
    // time (the H200 spent 1.5 s folding and 0.6 s rendering the hexroom at
    // 800x800, 64 spp), so it folds 8 times less often, and the CLI asks for
    // more samples per call. A pixel then sums at most about 80 samples in
    // float32 between folds: a relative rounding error near 1e-6.
    chosen.iterations_per_flush = cpu ? 32u : 256u;
    chosen.samples_per_call = !chosen.regeneration ? 1u : (cpu ? 8u : 32u);
    return chosen;
}

WavefrontIntegrator::WavefrontIntegrator(DeviceContext& device, const Scene& scene,
                                         IntegratorOptions options)
    : WavefrontIntegrator(device, prepare_scene(scene, options)) {}

WavefrontIntegrator::WavefrontIntegrator(DeviceContext& device, const PreparedScene& prepared)
    : device_(device), features_(prepared.features), options_(prepared.options),
      group_size_(wp::work_group_size_for(device.info)) {
    const DeviceScene& scene = *prepared.device_scene;
    const int width = prepared.width, height = prepared.height;
    pixel_count_ = static_cast<std::uint32_t>(width) * static_cast<std::uint32_t>(height);
    pool_size_ =
        options_.pool_size == 0 ? pixel_count_ : std::min(options_.pool_size, pixel_count_);
    check_device_memory(device_.info, width, height, pool_size_, options_.aovs != 0);

    SceneFeatures compiled = compiled_features(features_, options_);
    std::string build_options = kernel_build_options(compiled, options_);
    if (!options_.general_kernels) {
        build_options = with_injected_fault(build_options); // test only: as is unless asked for
        const SceneFeatures general = SceneFeatures::general_for(features_);
        const std::string general_options = kernel_build_options(general, options_);
        if (self_check_enabled(options_) && build_options != general_options) {
            self_check_ = check_kernels(device_, prepared);
            if (!self_check_->passed) {
                std::cerr << "wavepath: warning: on " << device_.info.name << " (driver "
                          << device_.info.driver_version
                          << ") the specialised kernels render differently from the general "
                             "ones ("
                          << self_check_->detail << (self_check_->from_cache ? ", remembered" : "")
                          << "); using the general kernels. The specialised build had: "
                          << features_.describe() << "\n";
                compiled = general;
                build_options = general_options;
            }
        }
    }
    plan_ = choose_launch_plan(options_.launch_plan, device_.info,
                               compiled.fixed_counts && !compiled.bvh, options_.regeneration,
                               options_.shade_order);
    // The wave's tail in one launch (kernels/tail.cl): only where waves have
    // tails (without regeneration the queue drains; with it, it refills), and
    // not with the sort, whose point is shade's order; never in the wave plan.
    if (plan_.plan != LaunchPlan::Wave && !plan_.regeneration && !plan_.sorted_shading)
        tail_rays_ = tail_rays_for(options_.tail_rays, pool_size_);
    check_scene_memory(device_.info, scene);
    program_ = build_wavefront_program(device_.context, device_.info.device, build_options,
                                       options_.program_cache);
    mirror_shadows_ = build_options.find("WP_MIRROR_NEE=1") != std::string::npos;
    if (mirror_shadows_)
        mirror_shadow_kernel_ = cl::Kernel(program_.program, "mirror_shadow");
    for (std::size_t i = 0; i < kStageKernelNames.size(); ++i)
        kernels_[i] = cl::Kernel(program_.program, std::string(kStageKernelNames[i]).c_str());
    if (plan_.sorted_shading)
        shade_sort_count_kernel_ = cl::Kernel(program_.program, "shade_sort_count");

    frame_.camera = scene.camera;
    frame_.width = static_cast<wp_uint>(width);
    frame_.height = static_cast<wp_uint>(height);
    frame_.seed = options_.seed;
    frame_.pool_size = pool_size_;
    frame_.triangle_count = static_cast<wp_uint>(scene.triangles.size());
    frame_.sphere_count = static_cast<wp_uint>(scene.spheres.size());
    frame_.light_count = static_cast<wp_uint>(scene.lights.size());
    frame_.light_area = scene.light_area;
    frame_.mirror_group_count = static_cast<wp_uint>(scene.mirror_groups.size());
    frame_.mirror_sphere_count = static_cast<wp_uint>(scene.mirror_spheres.size());
    frame_.emitter_count = static_cast<wp_uint>(scene.emitters.size());
    frame_.emitter_pick = scene.emitter_pick;
    frame_.instance_count = static_cast<wp_uint>(scene.instances.size());
    // The kernels' max_depth is the depth of the last vertex shaded: under
    // Mitsuba's rule (M edges at most) the vertex at depth M - 1, where the
    // path ends (kernels/shade.cl); under wavepath's the last bounce's.
    frame_.max_depth =
        options_.depth_rule == DepthRule::PathLength ? options_.max_depth - 1u : options_.max_depth;
    frame_.path_types = options_.path_types;

    buffers_ = allocate_device_buffers(device_.context, device_.info.device, prepared.device_scene,
                                       pool_size_, pixel_count_, options_.aovs != 0);
    clear_film();
    for (cl::Kernel& kernel : kernels_)
        bind_buffers(kernel, buffers_);
    if (mirror_shadows_)
        bind_buffers(mirror_shadow_kernel_, buffers_);
    if (plan_.sorted_shading)
        bind_buffers(shade_sort_count_kernel_, buffers_);
}

std::string WavefrontIntegrator::launch_summary() const {
    return to_string(plan_.plan) + (plan_.sorted_shading ? ", shade sorted by material" : "") +
           (plan_.regeneration ? ", regeneration" : ", one wave at a time") +
           (tail_rays_ > 0 ? ", its tail in one launch from " + std::to_string(tail_rays_) + " rays"
                           : "") +
           ", pool " + std::to_string(pool_size_) + ", work-groups of " +
           std::to_string(group_size_);
}

void WavefrontIntegrator::clear_film() {
    const cl_float4 zero4{};
    for (cl::Buffer* b : {&buffers_.film_sum, &buffers_.film_sum_squares, &buffers_.film_odd_sum})
        device_.queue.enqueueFillBuffer(*b, zero4, 0, sizeof(cl_float4) * pixel_count_);
    if (options_.aovs != 0) {
        for (cl::Buffer* b : {&buffers_.aov_albedo, &buffers_.aov_normal})
            device_.queue.enqueueFillBuffer(*b, zero4, 0, sizeof(cl_float4) * pixel_count_);
        device_.queue.enqueueFillBuffer(buffers_.aov_depth, cl_float{0.0f}, 0,
                                        sizeof(cl_float) * pixel_count_);
    }
}

void WavefrontIntegrator::launch(Stage stage, const WpLaunch& arguments, std::uint32_t items,
                                 cl::Kernel* other) {
    if (items == 0)
        return;
    cl::Kernel& kernel = other ? *other : kernels_[static_cast<std::size_t>(stage)];
    kernel.setArg(kFrameArgument, frame_);
    kernel.setArg(kLaunchArgument, arguments);
    std::size_t group = group_size_;
    std::size_t global = (items + group - 1) / group * group;
    cl::Event* event = profiler_ ? profiler_->begin(stage, items) : nullptr;
    device_.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global),
                                       cl::NDRange(group), nullptr, event);
}

void WavefrontIntegrator::read(const cl::Buffer& buffer, std::size_t bytes, void* out,
                               bool blocking) {
    cl::Event* event = profiler_ ? profiler_->begin(Stage::Transfer, bytes) : nullptr;
    device_.queue.enqueueReadBuffer(buffer, blocking ? CL_TRUE : CL_FALSE, 0, bytes, out, nullptr,
                                    event);
}

void WavefrontIntegrator::flush_film(Film& film) {
    const std::size_t floats = static_cast<std::size_t>(pixel_count_) * 4;
    std::vector<float> sum(floats), squares(floats), odd_sum(floats);
    read(buffers_.film_sum, floats * sizeof(float), sum.data(), false);
    read(buffers_.film_sum_squares, floats * sizeof(float), squares.data(), false);
    std::vector<float> albedo, normal, depth;
    if (options_.aovs != 0) {
        albedo.resize(floats);
        normal.resize(floats);
        depth.resize(pixel_count_);
        read(buffers_.aov_albedo, floats * sizeof(float), albedo.data(), false);
        read(buffers_.aov_normal, floats * sizeof(float), normal.data(), false);
        read(buffers_.aov_depth, depth.size() * sizeof(float), depth.data(), false);
    }
    read(buffers_.film_odd_sum, floats * sizeof(float), odd_sum.data(), true);
    clear_film();
    auto start = std::chrono::steady_clock::now();
    film.add_batch(sum, squares, odd_sum);
    if (options_.aovs != 0)
        film.add_aov_batch(albedo, normal, depth);
    stats_.host_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::uint32_t WavefrontIntegrator::max_samples_per_call(std::uint64_t pixels, std::uint64_t pool) {
    const std::uint64_t owned = (pixels + pool - 1) / pool; // pixels of the busiest slot
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(1, 0xffffffffu / owned));
}

void WavefrontIntegrator::render(std::uint32_t first_sample, std::uint32_t count, Film& film,
                                 const std::function<void(double)>& on_progress) {
    // A slot's task counter is 32 bits: (pixels it owns) x (samples in one
    // call) must stay below 2^32, so a huge image on a small pool renders in
    // several calls (the counter-based random numbers make that invisible).
    const std::uint32_t most = max_samples_per_call(pixel_count_, pool_size_);
    for (std::uint32_t done = 0; done < count;) {
        std::uint32_t part = std::min(count - done, most);
        render_range(first_sample + done, part, film, [&](double spp) {
            if (on_progress)
                on_progress(done + spp);
        });
        done += part;
    }
}

void WavefrontIntegrator::render_range(std::uint32_t first_sample, std::uint32_t count, Film& film,
                                       const std::function<void(double)>& on_progress) {
    if (count == 0)
        return;
    auto start = std::chrono::steady_clock::now();
    cl::CommandQueue& q = device_.queue;
    frame_.first_sample = first_sample;
    frame_.sample_count = count;
    q.enqueueFillBuffer(buffers_.path_task, cl_uint{0}, 0, sizeof(cl_uint) * pool_size_);
    q.enqueueFillBuffer(buffers_.counters, cl_uint{0}, 0, sizeof(cl_uint) * WP_COUNTER_COUNT);
    if (plan_.plan == LaunchPlan::Wave)
        trace_waves(count, film, on_progress);
    else
        trace_bounces(film, on_progress);
    flush_film(film);

    std::array<cl_uint, WP_COUNTER_COUNT> counters{};
    read(buffers_.counters, sizeof(counters), counters.data(), true);
    stats_.capped_paths += counters[WP_COUNTER_CAPPED];
    stats_.nonfinite_samples += counters[WP_COUNTER_NONFINITE];
    if (profiler_)
        profiler_->resolve_completed();
    stats_.render_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void WavefrontIntegrator::trace_bounces(Film& film,
                                        const std::function<void(double)>& on_progress) {
    const bool fused = plan_.plan == LaunchPlan::Bounce;
    // The launches per iteration whose items are the queue's rays: bounce,
    // or intersect, (the sort's two,) shade.
    const std::size_t ray_launches = fused ? 1 : plan_.sorted_shading ? 4 : 2;
    cl::CommandQueue& q = device_.queue;
    // The wave's tail in one launch (kernels/tail.cl): without regeneration
    // (with it the queue refills and has no tail), and not with the sort,
    // whose point is shade's order.
    const std::uint32_t tail_rays = tail_rays_;

    // The two ray queues swap roles every iteration: intersect and shade read
    // queue `in`, shade pushes survivors onto the other one, and generate
    // refills into that one too, so survivors and new camera rays form the
    // next iteration's input together. A queue's number is also the index of
    // its length in the counters.
    cl_uint in = WP_COUNTER_QUEUE_A;
    static_assert(WP_COUNTER_QUEUE_A == 0 && WP_COUNTER_QUEUE_B == 1);

    // The first wave: every slot gets a camera ray.
    launch(Stage::Generate, make_launch(pool_size_, in), pool_size_);
    // The profiler record of the last generate launch, whose item count (the
    // slots that really got a sample) is known only at the next sync; a
    // sentinel rather than std::optional, which GCC 12 wrongly calls
    // maybe-uninitialized here.
    constexpr std::size_t kNoRecord = static_cast<std::size_t>(-1);
    std::size_t generate_record = kNoRecord;
    if (profiler_)
        generate_record = profiler_->last_record();

    std::uint64_t upper_bound = pool_size_; // the most rays the input queue can hold
    std::uint64_t survivors = 0;            // of those, rays that shade pushed (the rest are new)
    std::uint64_t finished_total = 0;
    // Every slot owns its pixels and each of them gets sample_count samples
    // (kernels/generate.cl), each finishing exactly once.
    const std::uint64_t samples_total =
        static_cast<std::uint64_t>(pixel_count_) * static_cast<std::uint64_t>(frame_.sample_count);
    std::size_t bounce = 0; // iterations since the last wave started (without regeneration)
    const double pixels = static_cast<double>(pixel_count_);
    static const std::array<cl_uint, 2> zeros{0, 0};
    for (std::uint64_t iteration = 0;; ++iteration) {
        const cl_uint out = 1u - in;
        // Empty the output queue and the shadow and finished queues.
        q.enqueueWriteBuffer(buffers_.counters, CL_FALSE, sizeof(cl_uint) * out, sizeof(cl_uint),
                             zeros.data());
        q.enqueueWriteBuffer(buffers_.counters, CL_FALSE, sizeof(cl_uint) * WP_COUNTER_SHADOW_RAYS,
                             2 * sizeof(cl_uint), zeros.data());
        if (mirror_shadows_)
            q.enqueueWriteBuffer(buffers_.counters, CL_FALSE,
                                 sizeof(cl_uint) * WP_COUNTER_MIRROR_SHADOW_RAYS, sizeof(cl_uint),
                                 zeros.data());
        const auto bound = static_cast<std::uint32_t>(upper_bound);
        if (bound > 0 && bound <= tail_rays) {
            // At most `bound` rays are left of this wave: the tail kernel
            // traces them on for the iterations until the next fold of the
            // film (or WP_TAIL_BOUNCES), so that every path ends in the film
            // batch it ends in under the stages plan.
            const std::uint32_t span = std::min<std::uint32_t>(
                plan_.iterations_per_flush -
                    static_cast<std::uint32_t>(iteration % plan_.iterations_per_flush),
                WP_TAIL_BOUNCES);
            static const std::array<cl_uint, WP_TAIL_BOUNCES> no_lengths{};
            q.enqueueWriteBuffer(buffers_.tail_lengths, CL_FALSE, 0, sizeof(no_lengths),
                                 no_lengths.data());
            launch(Stage::Tail, make_launch(span, in), bound);
            std::optional<std::size_t> record;
            if (profiler_)
                record = profiler_->last_record();
            std::array<cl_uint, WP_COUNTER_MIRROR_SHADOW_RAYS + 1> counts{};
            read(buffers_.counters, 4 * sizeof(cl_uint), counts.data(), false);
            std::array<cl_uint, WP_TAIL_BOUNCES> lengths{};
            read(buffers_.tail_lengths, sizeof(lengths), lengths.data(), true);
            const std::uint32_t started = counts[in];
            const std::uint32_t next = counts[out];
            const std::uint32_t finished = counts[WP_COUNTER_FINISHED];
            // The rays of each bounce: the paths that traced more than b.
            std::uint32_t bounces = 0;
            std::uint64_t rays = 0, live = started;
            for (std::uint32_t b = 0; b < span && live > 0; ++b) {
                if (stats_.rays_per_bounce.size() <= bounce)
                    stats_.rays_per_bounce.resize(bounce + 1, 0);
                stats_.rays_per_bounce[bounce++] += live;
                rays += live;
                live -= lengths[b];
                ++bounces;
            }
            stats_.iterations += 1;
            stats_.queue_lengths.push_back(static_cast<std::uint32_t>(rays));
            stats_.camera_rays += started - survivors;
            stats_.bounce_rays += rays - (started - survivors);
            stats_.shadow_rays += counts[WP_COUNTER_SHADOW_RAYS];
            if (profiler_) {
                profiler_->set_items(*record, rays);
                if (generate_record != kNoRecord)
                    profiler_->set_items(generate_record, started - survivors);
                generate_record = kNoRecord;
                profiler_->resolve_completed();
            }
            if (started == 0)
                break;
            launch(Stage::Accumulate, make_launch(finished, in), finished);
            finished_total += finished;
            if (on_progress)
                on_progress(static_cast<double>(finished_total) / pixels);
            if (finished_total == samples_total)
                break;
            upper_bound = next;
            if (next == 0) { // the wave has ended: the next one starts
                launch(Stage::Generate, make_launch(pool_size_, out), pool_size_);
                upper_bound += pool_size_;
                bounce = 0;
                if (profiler_)
                    generate_record = profiler_->last_record();
            }
            survivors = next;
            in = out;
            // The tail ran the stages plan's iterations [iteration, iteration
            // + bounces); the film is folded where that plan folds it.
            iteration += bounces - 1;
            if ((iteration + 1) % plan_.iterations_per_flush == 0)
                flush_film(film);
            continue;
        }
        // The records of this iteration's ray launches (intersect and shade,
        // or bounce), whose item counts the sync below gives.
        std::optional<std::size_t> first_ray_record;
        if (fused) {
            launch(Stage::Bounce, make_launch(0, in), bound);
        } else {
            launch(Stage::Intersect, make_launch(0, in), bound);
            if (plan_.sorted_shading) // the queue sorted by material (kernels/shade_sort.cl)
                sort_for_shade(in, bound);
            launch(Stage::Shade, make_launch(0, in, false, plan_.sorted_shading), bound);
        }
        if (profiler_ && bound > 0)
            first_ray_record = profiler_->last_record() - (ray_launches - 1);

        // The one synchronisation per iteration: how long each queue is.
        std::array<cl_uint, WP_COUNTER_MIRROR_SHADOW_RAYS + 1> counts{};
        read(buffers_.counters, mirror_shadows_ ? sizeof(counts) : 4 * sizeof(cl_uint),
             counts.data(), true);
        const std::uint32_t traced = counts[in];
        const std::uint32_t next = counts[out];
        const std::uint32_t shadows = counts[WP_COUNTER_SHADOW_RAYS];
        const std::uint32_t finished = counts[WP_COUNTER_FINISHED];
        stats_.iterations += 1;
        stats_.queue_lengths.push_back(traced);
        if (!plan_.regeneration && traced > 0) {
            if (stats_.rays_per_bounce.size() <= bounce)
                stats_.rays_per_bounce.resize(bounce + 1, 0);
            stats_.rays_per_bounce[bounce++] += traced;
        }
        stats_.camera_rays += traced - survivors;
        stats_.bounce_rays += survivors;
        stats_.shadow_rays += shadows;
        if (profiler_) {
            // Launches were sized for the most the queues could hold; now the
            // device has said how many items there really were.
            if (first_ray_record)
                for (std::size_t r = *first_ray_record; r < *first_ray_record + ray_launches; ++r)
                    profiler_->set_items(r, traced);
            if (generate_record != kNoRecord)
                profiler_->set_items(generate_record, traced - survivors);
            generate_record = kNoRecord;
            profiler_->resolve_completed();
        }
        if (traced == 0)
            break; // nothing to trace (the count of finished samples below stops it sooner)

        if (!fused) { // the bounce kernel traced its shadow rays already
            launch(Stage::Shadow, make_launch(shadows, in), shadows);
            if (const std::uint32_t mirrored = counts[WP_COUNTER_MIRROR_SHADOW_RAYS];
                mirrored > 0) {
                // Two-leg rays through planar mirrors (kernels/mirror_light.h),
                // after the plain ones, so that no two work-items add to one
                // slot at once.
                launch(Stage::Shadow, make_launch(mirrored, in), mirrored, &mirror_shadow_kernel_);
                stats_.shadow_rays += 2u * mirrored; // two legs each, as the profile counts them
                if (profiler_)
                    profiler_->set_items(profiler_->last_record(), 2u * mirrored);
            }
        }
        launch(Stage::Accumulate, make_launch(finished, in), finished);
        finished_total += finished;
        if (on_progress)
            on_progress(static_cast<double>(finished_total) / pixels);
        // The last sample has finished: a refill would find no slot with work,
        // yet the iteration after it would be launched over its bound (the
        // whole pool, without regeneration), and where intersect vectorises
        // every surplus item traces slot 0's ray (kernels/traverse.h): once
        // per call, a whole wave's first intersect for nothing
        // (docs/performance.md, "The stages plan's host loop: the empty last
        // iteration, and running ahead").
        if (finished_total == samples_total)
            break;

        // Refill: with regeneration the slots that just finished start their
        // next sample now; without, the pool waits until it has drained.
        upper_bound = next;
        const bool refill_finished = plan_.regeneration && finished > 0;
        const bool refill_all = !plan_.regeneration && next == 0;
        if (refill_finished || refill_all) {
            std::uint32_t slots = refill_finished ? finished : pool_size_;
            launch(Stage::Generate, make_launch(slots, out, refill_finished), slots);
            upper_bound += slots;
            if (refill_all)
                bounce = 0;
            if (profiler_)
                generate_record = profiler_->last_record();
        }
        survivors = next;
        in = out;
        // With one slot per pixel a pixel finishes a sample every two to four
        // iterations: between folds a pixel's float32 sums hold about
        // iterations_per_flush / 3 samples, and the (width x height x 48
        // byte) read stays rare.
        if ((iteration + 1) % plan_.iterations_per_flush == 0)
            flush_film(film);
    }
}

void WavefrontIntegrator::sort_for_shade(cl_uint queue, std::uint32_t bound) {
    static const std::array<cl_uint, 2 * WP_SHADE_KEY_COUNT> zeros{};
    device_.queue.enqueueWriteBuffer(buffers_.shade_key_counts, CL_FALSE, 0, sizeof(zeros),
                                     zeros.data());
    launch(Stage::ShadeSort, make_launch(0, queue), bound, &shade_sort_count_kernel_);
    launch(Stage::ShadeSort, make_launch(0, queue), bound);
}

void WavefrontIntegrator::trace_waves(std::uint32_t count, Film& film,
                                      const std::function<void(double)>& on_progress) {
    cl::CommandQueue& q = device_.queue;

    // Without regeneration a launch is one wave, one task per slot; with it a
    // slot runs several tasks back to back (regeneration within the
    // work-item). Every slot has at most `owned` x count tasks.
    const std::uint32_t per_launch = plan_.regeneration ? kWaveTasksPerFlush : 1u;
    const std::uint64_t owned = (pixel_count_ + pool_size_ - 1) / pool_size_;
    const std::uint64_t tasks = owned * count;
    const double pixels = static_cast<double>(pixel_count_);
    std::uint64_t finished_total = 0;
    std::uint64_t since_flush = 0; // tasks per slot since the film was folded
    static const std::array<cl_uint, 3> zeros{0, 0, 0};
    for (std::uint64_t done = 0; done < tasks; done += per_launch) {
        q.enqueueWriteBuffer(buffers_.counters, CL_FALSE, 0, 3 * sizeof(cl_uint), zeros.data());
        launch(Stage::Wave, make_launch(per_launch, 0), pool_size_);
        std::optional<std::size_t> record;
        if (profiler_)
            record = profiler_->last_record();
        std::array<cl_uint, 3> counts{};
        read(buffers_.counters, sizeof(counts), counts.data(), true);
        const std::uint32_t rays = counts[WP_COUNTER_QUEUE_A];
        const std::uint32_t samples = counts[WP_COUNTER_QUEUE_B];
        stats_.iterations += 1;
        stats_.queue_lengths.push_back(rays);
        stats_.camera_rays += samples;
        stats_.bounce_rays += rays - samples;
        stats_.shadow_rays += counts[WP_COUNTER_SHADOW_RAYS];
        if (profiler_) {
            profiler_->set_items(*record, samples);
            profiler_->resolve_completed();
        }
        if (samples == 0)
            break; // every slot has done all its tasks (a slot owning fewer pixels ends first)
        finished_total += samples;
        if (on_progress)
            on_progress(static_cast<double>(finished_total) / pixels);
        since_flush += per_launch;
        if (since_flush >= kWaveTasksPerFlush && done + per_launch < tasks) {
            flush_film(film);
            since_flush = 0;
        }
    }
}

// Stage benchmarks: rays written straight into the path (or shadow) state of
// slots 0 .. n-1, which the queue lists in order.
void WavefrontIntegrator::load_rays(const cl::Buffer& origin_buffer,
                                    const cl::Buffer& direction_buffer, const cl::Buffer& queue,
                                    const std::vector<cl_float4>& origins,
                                    const std::vector<cl_float4>& directions) {
    if (origins.size() != directions.size() || origins.size() > pool_size_)
        throw std::invalid_argument("stage benchmark: more rays than path slots");
    cl::CommandQueue& q = device_.queue;
    const std::size_t n = origins.size();
    std::vector<cl_uint> identity(n);
    std::iota(identity.begin(), identity.end(), 0u);
    q.enqueueWriteBuffer(origin_buffer, CL_TRUE, 0, sizeof(cl_float4) * n, origins.data());
    q.enqueueWriteBuffer(direction_buffer, CL_TRUE, 0, sizeof(cl_float4) * n, directions.data());
    q.enqueueWriteBuffer(queue, CL_TRUE, 0, sizeof(cl_uint) * n, identity.data());
}

double WavefrontIntegrator::time_intersect(const std::vector<cl_float4>& origins,
                                           const std::vector<cl_float4>& directions,
                                           int repetitions) {
    load_rays(buffers_.ray_origin, buffers_.ray_direction, buffers_.ray_queues, origins,
              directions);
    const auto n = static_cast<cl_uint>(origins.size());
    std::array<cl_uint, 1> count{n};
    device_.queue.enqueueWriteBuffer(buffers_.counters, CL_TRUE,
                                     sizeof(cl_uint) * WP_COUNTER_QUEUE_A, sizeof(cl_uint),
                                     count.data());
    return time_launches(Stage::Intersect, make_launch(0, WP_COUNTER_QUEUE_A), n, repetitions);
}

double WavefrontIntegrator::time_shadow(const std::vector<cl_float4>& origins,
                                        const std::vector<cl_float4>& directions, int repetitions) {
    load_rays(buffers_.shadow_origin, buffers_.shadow_direction, buffers_.shadow_queue, origins,
              directions);
    const auto n = static_cast<cl_uint>(origins.size());
    return time_launches(Stage::Shadow, make_launch(n, 0), n, repetitions);
}

double WavefrontIntegrator::time_launches(Stage stage, const WpLaunch& arguments,
                                          std::uint32_t items, int repetitions) {
    Profiler local;
    Profiler* saved = profiler_;
    profiler_ = &local;
    for (int r = 0; r < repetitions; ++r)
        launch(stage, arguments, items);
    device_.queue.finish();
    local.resolve_completed();
    profiler_ = saved;
    return local.device_busy_seconds();
}

SceneFeatures integrator_features(const Scene& scene, const IntegratorOptions& options) {
    SceneFeatures features = analyse_features(scene);
    if (options.traversal == Traversal::Loop && features.instances)
        throw std::runtime_error("--traversal loop: a scene with instances is traced through its "
                                 "hierarchy only (docs/instancing.md)");
    if (options.traversal != Traversal::Auto) {
        features.bvh = options.traversal == Traversal::Hierarchy;
        if (features.bvh)
            features.fixed_counts = false;
    }
    if (!options.shadow_culling)
        features.shadow_culling = false;
    if (options.light_pick == LightPick::Area)
        features.power_light_pick = false;
    return features;
}

SceneFeatures compiled_features(const SceneFeatures& features, const IntegratorOptions& options) {
    return options.general_kernels ? SceneFeatures::general_for(features) : features;
}

std::string kernel_build_options(const SceneFeatures& features, const IntegratorOptions& options) {
    std::string text = features.build_options();
    if (!options.next_event_estimation)
        text += " -D WP_USE_NEE=0";
    text += options.diffuse_sampling == DiffuseSampling::Report ? " -D WP_DIFFUSE_SAMPLING=1"
                                                                : " -D WP_DIFFUSE_SAMPLING=0";
    text += options.light_sampling == LightSampling::SolidAngle ? " -D WP_LIGHT_SAMPLING=1"
                                                                : " -D WP_LIGHT_SAMPLING=0";
    text += " -D WP_ROULETTE_DEPTH=" + std::to_string(options.roulette_depth);
    if (options.roulette_rule == RouletteRule::Mitsuba) // only then: the default builds as it was
        text += " -D WP_ROULETTE_RULE=1";
    else if (options.roulette_rule == RouletteRule::Sqrt)
        text += " -D WP_ROULETTE_RULE=2";
    else if (options.roulette_rule == RouletteRule::Relative)
        text += " -D WP_ROULETTE_RULE=3";
    if (options.mis == MisStrategy::LightOnly) // only then: the default builds are as they were
        text += " -D WP_MIS_STRATEGY=1";
    if (options.path_types != kAllPathTypes) // only then is anything tracked (path_type.h)
        text += " -D WP_PATH_TYPES=1";
    text += options.sampler == Sampler::Sobol ? " -D WP_SAMPLER=1" : " -D WP_SAMPLER=0";
    if ((features.planar_mirrors || features.mirror_spheres) && options.next_event_estimation &&
        options.mirror_next_event)
        text += " -D WP_MIRROR_NEE=1";
    if (features.shading_normals && !options.shadow_terminator_fix)
        text += " -D WP_SHADOW_TERMINATOR_FIX=0";
    if (options.aovs != 0) // only then: without, the kernels are as they were
        text += " -D WP_AOV=1";
    if (options.depth_rule == DepthRule::PathLength) // only then: the default is as it was
        text += " -D WP_PATH_LENGTH=1";
    return text;
}

} // namespace wp
