#include "render/wavefront.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace wp {
namespace {

// Iterations between folding the device's float32 film into the host's
// double film. With one slot per pixel a pixel finishes a sample every two
// to four iterations, so a batch holds about ten samples: float32 sums stay
// accurate and the (width x height x 48 byte) read stays rare.
constexpr std::uint64_t kIterationsPerFlush = 32;

// Launches use work-groups of this size (or the device's maximum, if smaller)
// and round the item count up to a multiple; kernels ignore the excess items
// and never depend on the group size. A fixed size matters on PoCL, which
// compiles a kernel anew for every distinct local size it is given.
constexpr std::uint32_t kWorkGroupSize = 64;

// Device memory per path slot: nine float4 arrays (ray origin and direction,
// throughput, radiance, the shadow ray's origin, direction and contribution)
// and eleven 4-byte arrays (task, pixel, sample, depth, flags, hit distance
// and primitive, the slot list, two ray queues, the finished and shadow
// queues); per pixel: three float4 film sums.
constexpr std::uint64_t kBytesPerSlot = 7 * sizeof(cl_float4) + 12 * sizeof(cl_uint);
constexpr std::uint64_t kBytesPerPixel = 3 * sizeof(cl_float4);

template <typename T> cl::Buffer upload(const cl::Context& context, const std::vector<T>& data) {
    // OpenCL has no empty buffers; a one-element dummy stands in.
    std::vector<T> padded = data.empty() ? std::vector<T>(1) : data;
    return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(T) * padded.size(),
                      padded.data());
}

cl::Buffer device_array(const cl::Context& context, std::size_t element_size, std::size_t count) {
    return cl::Buffer(context, CL_MEM_READ_WRITE, element_size * std::max<std::size_t>(count, 1));
}

std::string gibibytes(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f GiB", static_cast<double>(bytes) / (1ull << 30));
    return text;
}

// Fails with a clear message before allocating what the device cannot hold
// (drivers report this late and vaguely, if at all).
void check_device_memory(const DeviceInfo& device, int width, int height, std::uint64_t slots) {
    const std::uint64_t pixels =
        static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    const std::uint64_t total = pixels * kBytesPerPixel + slots * kBytesPerSlot;
    const std::uint64_t largest = std::max(pixels, slots) * sizeof(cl_float4);
    const std::uint64_t max_alloc = device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    if (total > device.global_memory_bytes || largest > max_alloc)
        throw std::runtime_error(
            "out of device memory: a " + std::to_string(width) + "x" + std::to_string(height) +
            " image needs " + gibibytes(total) + " (largest buffer " + gibibytes(largest) +
            ") on " + device.name + ", which has " + gibibytes(device.global_memory_bytes) +
            " (largest buffer " + gibibytes(max_alloc) + "); use a smaller --width/--height");
}

} // namespace

WavefrontIntegrator::WavefrontIntegrator(DeviceContext& device, const Scene& scene,
                                         IntegratorOptions options)
    : device_(device), scene_(flatten_scene(scene)), features_(analyse_features(scene)),
      options_(options) {
    pixel_count_ =
        static_cast<std::uint32_t>(scene_.width) * static_cast<std::uint32_t>(scene_.height);
    pool_size_ =
        options_.pool_size == 0 ? pixel_count_ : std::min(options_.pool_size, pixel_count_);
    check_device_memory(device_.info, scene_.width, scene_.height, pool_size_);

    const cl::Context& ctx = device_.context;
    SceneFeatures compiled = options_.general_kernels ? SceneFeatures::all() : features_;
    std::string build_options = compiled.build_options();
    if (!options_.next_event_estimation)
        build_options += " -D WP_USE_NEE=0";
    build_options += options_.diffuse_sampling == DiffuseSampling::Report
                         ? " -D WP_DIFFUSE_SAMPLING=1"
                         : " -D WP_DIFFUSE_SAMPLING=0";
    build_options += options_.light_sampling == LightSampling::SolidAngle
                         ? " -D WP_LIGHT_SAMPLING=1"
                         : " -D WP_LIGHT_SAMPLING=0";
    program_ =
        build_wavefront_program(ctx, device_.info.device, build_options, options_.program_cache);

    generate_ = cl::Kernel(program_.program, "generate");
    intersect_ = cl::Kernel(program_.program, "intersect");
    shade_ = cl::Kernel(program_.program, "shade");
    shadow_ = cl::Kernel(program_.program, "shadow");
    accumulate_ = cl::Kernel(program_.program, "accumulate");

    frame_.camera = scene_.camera;
    frame_.width = static_cast<wp_uint>(scene_.width);
    frame_.height = static_cast<wp_uint>(scene_.height);
    frame_.seed = options_.seed;
    frame_.pool_size = pool_size_;
    frame_.triangle_count = static_cast<wp_uint>(scene_.triangles.size());
    frame_.sphere_count = static_cast<wp_uint>(scene_.spheres.size());
    frame_.light_count = static_cast<wp_uint>(scene_.lights.size());
    frame_.light_area = scene_.light_area;
    frame_.max_depth = options_.max_depth;

    triangles_ = upload(ctx, scene_.triangles);
    spheres_ = upload(ctx, scene_.spheres);
    materials_ = upload(ctx, scene_.materials);
    lights_ = upload(ctx, scene_.lights);

    const std::size_t n = pool_size_;
    const std::size_t f4 = sizeof(cl_float4), u = sizeof(cl_uint);
    path_task_ = device_array(ctx, u, n);
    ray_origin_ = device_array(ctx, f4, n);
    ray_direction_ = device_array(ctx, f4, n);
    throughput_ = device_array(ctx, f4, n);
    radiance_ = device_array(ctx, f4, n);
    path_pixel_ = device_array(ctx, u, n);
    path_sample_ = device_array(ctx, u, n);
    path_depth_ = device_array(ctx, u, n);
    path_flags_ = device_array(ctx, u, n);
    hit_t_ = device_array(ctx, sizeof(cl_float), n);
    hit_primitive_ = device_array(ctx, u, n);
    shadow_origin_ = device_array(ctx, f4, n);
    shadow_direction_ = device_array(ctx, f4, n);
    shadow_contribution_ = device_array(ctx, f4, n);
    std::vector<cl_uint> identity(n);
    std::iota(identity.begin(), identity.end(), 0u);
    all_slots_ = upload(ctx, identity);
    queue_a_ = device_array(ctx, u, n);
    queue_b_ = device_array(ctx, u, n);
    finished_queue_ = device_array(ctx, u, n);
    shadow_queue_ = device_array(ctx, u, n);
    counters_ = device_array(ctx, u, WP_COUNTER_COUNT);
    film_sum_ = device_array(ctx, f4, pixel_count_);
    film_sum_squares_ = device_array(ctx, f4, pixel_count_);
    film_odd_sum_ = device_array(ctx, f4, pixel_count_);

    const cl_float4 zero4{};
    for (cl::Buffer* b : {&film_sum_, &film_sum_squares_, &film_odd_sum_})
        device_.queue.enqueueFillBuffer(*b, zero4, 0, f4 * pixel_count_);

    // Buffer arguments that never change; the frame, queue roles and lengths
    // are set per launch.
    generate_.setArg(3, path_task_);
    generate_.setArg(4, ray_origin_);
    generate_.setArg(5, ray_direction_);
    generate_.setArg(6, throughput_);
    generate_.setArg(7, radiance_);
    generate_.setArg(8, path_pixel_);
    generate_.setArg(9, path_sample_);
    generate_.setArg(10, path_depth_);
    generate_.setArg(11, path_flags_);
    generate_.setArg(13, counters_);

    intersect_.setArg(2, counters_);
    intersect_.setArg(4, ray_origin_);
    intersect_.setArg(5, ray_direction_);
    intersect_.setArg(6, triangles_);
    intersect_.setArg(7, spheres_);
    intersect_.setArg(8, hit_t_);
    intersect_.setArg(9, hit_primitive_);

    shade_.setArg(2, counters_);
    shade_.setArg(6, finished_queue_);
    shade_.setArg(7, ray_origin_);
    shade_.setArg(8, ray_direction_);
    shade_.setArg(9, hit_t_);
    shade_.setArg(10, hit_primitive_);
    shade_.setArg(11, throughput_);
    shade_.setArg(12, radiance_);
    shade_.setArg(13, path_depth_);
    shade_.setArg(14, path_flags_);
    shade_.setArg(15, path_pixel_);
    shade_.setArg(16, path_sample_);
    shade_.setArg(17, triangles_);
    shade_.setArg(18, spheres_);
    shade_.setArg(19, materials_);
    shade_.setArg(20, lights_);
    shade_.setArg(21, shadow_queue_);
    shade_.setArg(22, shadow_origin_);
    shade_.setArg(23, shadow_direction_);
    shade_.setArg(24, shadow_contribution_);

    shadow_.setArg(2, shadow_queue_);
    shadow_.setArg(3, shadow_origin_);
    shadow_.setArg(4, shadow_direction_);
    shadow_.setArg(5, shadow_contribution_);
    shadow_.setArg(6, triangles_);
    shadow_.setArg(7, spheres_);
    shadow_.setArg(8, radiance_);

    accumulate_.setArg(1, finished_queue_);
    accumulate_.setArg(3, radiance_);
    accumulate_.setArg(4, path_pixel_);
    accumulate_.setArg(5, path_sample_);
    accumulate_.setArg(6, film_sum_);
    accumulate_.setArg(7, film_sum_squares_);
    accumulate_.setArg(8, film_odd_sum_);
    accumulate_.setArg(9, counters_);
}

void WavefrontIntegrator::launch(cl::Kernel& kernel, std::uint32_t items, Stage stage) {
    if (items == 0)
        return;
    std::size_t group = std::min<std::size_t>(kWorkGroupSize, device_.info.max_work_group_size);
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

void WavefrontIntegrator::set_queue_arguments(cl::Buffer& in, cl_uint in_counter, cl::Buffer& out,
                                              cl_uint out_counter) {
    intersect_.setArg(1, in);
    intersect_.setArg(3, in_counter);
    shade_.setArg(1, in);
    shade_.setArg(3, in_counter);
    shade_.setArg(4, out);
    shade_.setArg(5, out_counter);
    // generate refills into the queue shade fills, so survivors and new
    // camera rays form the next iteration's input together.
    generate_.setArg(12, out);
    generate_.setArg(14, out_counter);
}

void WavefrontIntegrator::flush_film(Film& film) {
    const std::size_t floats = static_cast<std::size_t>(pixel_count_) * 4;
    std::vector<float> sum(floats), squares(floats), odd_sum(floats);
    read(film_sum_, floats * sizeof(float), sum.data(), false);
    read(film_sum_squares_, floats * sizeof(float), squares.data(), false);
    read(film_odd_sum_, floats * sizeof(float), odd_sum.data(), true);
    const cl_float4 zero4{};
    for (cl::Buffer* b : {&film_sum_, &film_sum_squares_, &film_odd_sum_})
        device_.queue.enqueueFillBuffer(*b, zero4, 0, floats * sizeof(float));
    auto start = std::chrono::steady_clock::now();
    film.add_batch(sum, squares, odd_sum);
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
    for (cl::Kernel* k : {&generate_, &intersect_, &shade_, &shadow_, &accumulate_})
        k->setArg(0, frame_);
    q.enqueueFillBuffer(path_task_, cl_uint{0}, 0, sizeof(cl_uint) * pool_size_);
    q.enqueueFillBuffer(counters_, cl_uint{0}, 0, sizeof(cl_uint) * WP_COUNTER_COUNT);

    cl::Buffer* in = &queue_a_;
    cl::Buffer* out = &queue_b_;
    cl_uint in_counter = WP_COUNTER_QUEUE_A, out_counter = WP_COUNTER_QUEUE_B;

    // The first wave: every slot gets a camera ray.
    generate_.setArg(1, all_slots_);
    generate_.setArg(2, pool_size_);
    generate_.setArg(12, *in);
    generate_.setArg(14, in_counter);
    launch(generate_, pool_size_, Stage::Generate);
    // The profiler record of the last generate launch, whose item count (the
    // slots that really got a sample) is known only at the next sync.
    std::optional<std::size_t> generate_record;
    if (profiler_)
        generate_record = profiler_->last_record();

    std::uint64_t upper_bound = pool_size_; // the most rays the input queue can hold
    std::uint64_t survivors = 0;            // of those, rays that shade pushed (the rest are new)
    std::uint64_t finished_total = 0;
    std::size_t bounce = 0; // iterations since the last wave started (without regeneration)
    const double pixels = static_cast<double>(pixel_count_);
    static const std::array<cl_uint, 2> zeros{0, 0};
    for (std::uint64_t iteration = 0;; ++iteration) {
        // Empty the output queue and the shadow and finished queues.
        q.enqueueWriteBuffer(counters_, CL_FALSE, sizeof(cl_uint) * out_counter, sizeof(cl_uint),
                             zeros.data());
        q.enqueueWriteBuffer(counters_, CL_FALSE, sizeof(cl_uint) * WP_COUNTER_SHADOW_RAYS,
                             2 * sizeof(cl_uint), zeros.data());
        set_queue_arguments(*in, in_counter, *out, out_counter);
        const auto bound = static_cast<std::uint32_t>(upper_bound);
        launch(intersect_, bound, Stage::Intersect);
        launch(shade_, bound, Stage::Shade);

        // The one synchronisation per iteration: how long each queue is.
        std::array<cl_uint, 4> counts{};
        read(counters_, sizeof(counts), counts.data(), true);
        const std::uint32_t traced = counts[in_counter];
        const std::uint32_t next = counts[out_counter];
        const std::uint32_t shadows = counts[WP_COUNTER_SHADOW_RAYS];
        const std::uint32_t finished = counts[WP_COUNTER_FINISHED];
        stats_.iterations += 1;
        stats_.queue_lengths.push_back(traced);
        if (!options_.regeneration && traced > 0) {
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
            if (bound > 0) {
                std::size_t shade_record = profiler_->last_record() - 1;
                profiler_->set_items(shade_record - 1, traced);
                profiler_->set_items(shade_record, traced);
            }
            if (generate_record)
                profiler_->set_items(*generate_record, traced - survivors);
            generate_record.reset();
            profiler_->resolve_completed();
        }
        if (traced == 0)
            break; // every slot has finished all its samples

        shadow_.setArg(1, shadows);
        launch(shadow_, shadows, Stage::Shadow);
        accumulate_.setArg(2, finished);
        launch(accumulate_, finished, Stage::Accumulate);
        finished_total += finished;
        if (on_progress)
            on_progress(static_cast<double>(finished_total) / pixels);

        // Refill: with regeneration the slots that just finished start their
        // next sample now; without, the pool waits until it has drained.
        upper_bound = next;
        const bool refill_finished = options_.regeneration && finished > 0;
        const bool refill_all = !options_.regeneration && next == 0;
        if (refill_finished || refill_all) {
            std::uint32_t slots = refill_finished ? finished : pool_size_;
            generate_.setArg(1, refill_finished ? finished_queue_ : all_slots_);
            generate_.setArg(2, slots);
            launch(generate_, slots, Stage::Generate);
            upper_bound += slots;
            if (refill_all)
                bounce = 0;
            if (profiler_)
                generate_record = profiler_->last_record();
        }
        survivors = next;
        std::swap(in, out);
        std::swap(in_counter, out_counter);
        if ((iteration + 1) % kIterationsPerFlush == 0)
            flush_film(film);
    }
    flush_film(film);

    std::array<cl_uint, WP_COUNTER_COUNT> counters{};
    read(counters_, sizeof(counters), counters.data(), true);
    stats_.capped_paths += counters[WP_COUNTER_CAPPED];
    stats_.nonfinite_samples += counters[WP_COUNTER_NONFINITE];
    if (profiler_)
        profiler_->resolve_completed();
    stats_.render_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double WavefrontIntegrator::time_intersect(const std::vector<cl_float4>& origins,
                                           const std::vector<cl_float4>& directions,
                                           int repetitions) {
    if (origins.size() != directions.size() || origins.size() > pool_size_)
        throw std::invalid_argument("time_intersect: more rays than path slots");
    cl::CommandQueue& q = device_.queue;
    const auto n = static_cast<cl_uint>(origins.size());
    q.enqueueWriteBuffer(ray_origin_, CL_TRUE, 0, sizeof(cl_float4) * n, origins.data());
    q.enqueueWriteBuffer(ray_direction_, CL_TRUE, 0, sizeof(cl_float4) * n, directions.data());
    q.enqueueCopyBuffer(all_slots_, queue_a_, 0, 0, sizeof(cl_uint) * n);
    std::array<cl_uint, 1> count{n};
    q.enqueueWriteBuffer(counters_, CL_TRUE, sizeof(cl_uint) * WP_COUNTER_QUEUE_A, sizeof(cl_uint),
                         count.data());
    intersect_.setArg(0, frame_);
    intersect_.setArg(1, queue_a_);
    intersect_.setArg(3, WP_COUNTER_QUEUE_A);
    return time_launches(intersect_, n, Stage::Intersect, repetitions);
}

double WavefrontIntegrator::time_shadow(const std::vector<cl_float4>& origins,
                                        const std::vector<cl_float4>& directions, int repetitions) {
    if (origins.size() != directions.size() || origins.size() > pool_size_)
        throw std::invalid_argument("time_shadow: more rays than path slots");
    cl::CommandQueue& q = device_.queue;
    const auto n = static_cast<cl_uint>(origins.size());
    q.enqueueWriteBuffer(shadow_origin_, CL_TRUE, 0, sizeof(cl_float4) * n, origins.data());
    q.enqueueWriteBuffer(shadow_direction_, CL_TRUE, 0, sizeof(cl_float4) * n, directions.data());
    q.enqueueCopyBuffer(all_slots_, shadow_queue_, 0, 0, sizeof(cl_uint) * n);
    shadow_.setArg(0, frame_);
    shadow_.setArg(1, n);
    return time_launches(shadow_, n, Stage::Shadow, repetitions);
}

double WavefrontIntegrator::time_launches(cl::Kernel& kernel, std::uint32_t items, Stage stage,
                                          int repetitions) {
    Profiler local;
    Profiler* saved = profiler_;
    profiler_ = &local;
    for (int r = 0; r < repetitions; ++r)
        launch(kernel, items, stage);
    device_.queue.finish();
    local.resolve_completed();
    profiler_ = saved;
    return local.device_busy_seconds();
}

} // namespace wp
