#include "render/wavefront.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <stdexcept>

namespace wp {
namespace {

// Waves added into the device's float32 film before the host folds them into
// its double-precision film: few enough that float32 sums stay accurate.
constexpr std::uint32_t kWavesPerFlush = 16;

// Launches use work-groups of this size (or the device's maximum, if smaller)
// and round the item count up to a multiple; kernels ignore the excess items
// and never depend on the group size. A fixed size matters on PoCL, which
// compiles a kernel anew for every distinct local size it is given.
constexpr std::uint32_t kWorkGroupSize = 64;

template <typename T> cl::Buffer upload(const cl::Context& context, const std::vector<T>& data) {
    // OpenCL has no empty buffers; a one-element dummy stands in.
    std::vector<T> padded = data.empty() ? std::vector<T>(1) : data;
    return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(T) * padded.size(),
                      padded.data());
}

cl::Buffer device_array(const cl::Context& context, std::size_t element_size, std::size_t count) {
    return cl::Buffer(context, CL_MEM_READ_WRITE, element_size * std::max<std::size_t>(count, 1));
}

// Device memory per pixel: ten float4 arrays (ray origin and direction,
// throughput, radiance, the shadow ray's origin, direction and contribution,
// three film sums) and eight 4-byte arrays (pixel, depth, flags, hit distance
// and primitive, two ray queues, the shadow queue).
constexpr std::uint64_t kBytesPerPixel = 10 * sizeof(cl_float4) + 8 * sizeof(cl_uint);

std::string gibibytes(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f GiB", static_cast<double>(bytes) / (1ull << 30));
    return text;
}

// Fails with a clear message before allocating what the device cannot hold
// (drivers report this late and vaguely, if at all).
void check_device_memory(const DeviceInfo& device, int width, int height) {
    const std::uint64_t pixels =
        static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    const std::uint64_t total = pixels * kBytesPerPixel;
    const std::uint64_t largest = pixels * sizeof(cl_float4);
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
    check_device_memory(device_.info, scene_.width, scene_.height);
    const cl::Context& ctx = device_.context;
    SceneFeatures compiled = options_.general_kernels ? SceneFeatures::all() : features_;
    std::string build_options = compiled.build_options();
    if (!options_.next_event_estimation)
        build_options += " -D WP_USE_NEE=0";
    program_ = build_wavefront_program(ctx, device_.info.device, build_options);

    generate_ = cl::Kernel(program_.program, "generate");
    intersect_ = cl::Kernel(program_.program, "intersect");
    shade_ = cl::Kernel(program_.program, "shade");
    shadow_ = cl::Kernel(program_.program, "shadow");
    accumulate_ = cl::Kernel(program_.program, "accumulate");

    pixel_count_ =
        static_cast<std::uint32_t>(scene_.width) * static_cast<std::uint32_t>(scene_.height);
    frame_.camera = scene_.camera;
    frame_.width = static_cast<wp_uint>(scene_.width);
    frame_.height = static_cast<wp_uint>(scene_.height);
    frame_.seed = options_.seed;
    frame_.triangle_count = static_cast<wp_uint>(scene_.triangles.size());
    frame_.sphere_count = static_cast<wp_uint>(scene_.spheres.size());
    frame_.light_count = static_cast<wp_uint>(scene_.lights.size());
    frame_.light_area = scene_.light_area;
    frame_.max_depth = options_.max_depth;

    triangles_ = upload(ctx, scene_.triangles);
    spheres_ = upload(ctx, scene_.spheres);
    materials_ = upload(ctx, scene_.materials);
    lights_ = upload(ctx, scene_.lights);

    const std::size_t n = pixel_count_;
    const std::size_t f4 = sizeof(cl_float4), u = sizeof(cl_uint);
    ray_origin_ = device_array(ctx, f4, n);
    ray_direction_ = device_array(ctx, f4, n);
    throughput_ = device_array(ctx, f4, n);
    radiance_ = device_array(ctx, f4, n);
    path_pixel_ = device_array(ctx, u, n);
    path_depth_ = device_array(ctx, u, n);
    path_flags_ = device_array(ctx, u, n);
    hit_t_ = device_array(ctx, sizeof(cl_float), n);
    hit_primitive_ = device_array(ctx, u, n);
    shadow_origin_ = device_array(ctx, f4, n);
    shadow_direction_ = device_array(ctx, f4, n);
    shadow_contribution_ = device_array(ctx, f4, n);
    queue_a_ = device_array(ctx, u, n);
    queue_b_ = device_array(ctx, u, n);
    shadow_queue_ = device_array(ctx, u, n);
    counters_ = device_array(ctx, u, WP_COUNTER_COUNT);
    film_sum_ = device_array(ctx, f4, n);
    film_sum_squares_ = device_array(ctx, f4, n);
    film_odd_sum_ = device_array(ctx, f4, n);

    cl::CommandQueue& q = device_.queue;
    const cl_float4 zero4{};
    for (cl::Buffer* b : {&film_sum_, &film_sum_squares_, &film_odd_sum_})
        q.enqueueFillBuffer(*b, zero4, 0, f4 * n);
    q.enqueueFillBuffer(counters_, cl_uint{0}, 0, u * WP_COUNTER_COUNT);

    // Buffer arguments never change; the frame and queue lengths do (set per launch).
    generate_.setArg(1, ray_origin_);
    generate_.setArg(2, ray_direction_);
    generate_.setArg(3, throughput_);
    generate_.setArg(4, radiance_);
    generate_.setArg(5, path_pixel_);
    generate_.setArg(6, path_depth_);
    generate_.setArg(7, path_flags_);
    generate_.setArg(8, queue_a_);

    intersect_.setArg(3, ray_origin_);
    intersect_.setArg(4, ray_direction_);
    intersect_.setArg(5, triangles_);
    intersect_.setArg(6, spheres_);
    intersect_.setArg(7, hit_t_);
    intersect_.setArg(8, hit_primitive_);

    shade_.setArg(3, ray_origin_);
    shade_.setArg(4, ray_direction_);
    shade_.setArg(5, hit_t_);
    shade_.setArg(6, hit_primitive_);
    shade_.setArg(7, throughput_);
    shade_.setArg(8, radiance_);
    shade_.setArg(9, path_depth_);
    shade_.setArg(10, path_flags_);
    shade_.setArg(11, path_pixel_);
    shade_.setArg(12, triangles_);
    shade_.setArg(13, spheres_);
    shade_.setArg(14, materials_);
    shade_.setArg(15, lights_);
    shade_.setArg(17, shadow_queue_);
    shade_.setArg(18, shadow_origin_);
    shade_.setArg(19, shadow_direction_);
    shade_.setArg(20, shadow_contribution_);
    shade_.setArg(21, counters_);

    shadow_.setArg(2, shadow_queue_);
    shadow_.setArg(3, shadow_origin_);
    shadow_.setArg(4, shadow_direction_);
    shadow_.setArg(5, shadow_contribution_);
    shadow_.setArg(6, triangles_);
    shadow_.setArg(7, spheres_);
    shadow_.setArg(8, radiance_);

    accumulate_.setArg(1, radiance_);
    accumulate_.setArg(2, path_pixel_);
    accumulate_.setArg(3, film_sum_);
    accumulate_.setArg(4, film_sum_squares_);
    accumulate_.setArg(5, film_odd_sum_);
    accumulate_.setArg(6, counters_);
}

void WavefrontIntegrator::launch(cl::Kernel& kernel, std::uint32_t items) {
    std::size_t group = std::min<std::size_t>(kWorkGroupSize, device_.info.max_work_group_size);
    std::size_t global = (items + group - 1) / group * group;
    device_.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global),
                                       cl::NDRange(group));
}

void WavefrontIntegrator::run_wave(std::uint32_t sample_index) {
    cl::CommandQueue& q = device_.queue;
    frame_.sample_index = sample_index;

    generate_.setArg(0, frame_);
    launch(generate_, pixel_count_);
    stats_.camera_rays += pixel_count_;

    cl::Buffer* in = &queue_a_;
    cl::Buffer* out = &queue_b_;
    std::uint32_t ray_count = pixel_count_;
    static const std::array<cl_uint, 2> zeros{0, 0};
    for (std::size_t depth = 0; ray_count > 0; ++depth) {
        if (stats_.rays_per_depth.size() <= depth)
            stats_.rays_per_depth.push_back(0);
        stats_.rays_per_depth[depth] += ray_count;
        if (depth > 0)
            stats_.bounce_rays += ray_count;

        // Reset the next-ray and shadow-ray counters (the first two).
        q.enqueueWriteBuffer(counters_, CL_FALSE, 0, sizeof(zeros), zeros.data());

        intersect_.setArg(0, frame_);
        intersect_.setArg(1, ray_count);
        intersect_.setArg(2, *in);
        launch(intersect_, ray_count);

        shade_.setArg(0, frame_);
        shade_.setArg(1, ray_count);
        shade_.setArg(2, *in);
        shade_.setArg(16, *out);
        launch(shade_, ray_count);

        std::array<cl_uint, 2> counts{};
        q.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(counts), counts.data());
        std::uint32_t shadow_count = counts[WP_COUNTER_SHADOW_RAYS];
        if (shadow_count > 0) {
            shadow_.setArg(0, frame_);
            shadow_.setArg(1, shadow_count);
            launch(shadow_, shadow_count);
            stats_.shadow_rays += shadow_count;
        }
        ray_count = counts[WP_COUNTER_NEXT_RAYS];
        std::swap(in, out);
    }

    accumulate_.setArg(0, frame_);
    launch(accumulate_, pixel_count_);
}

void WavefrontIntegrator::flush_film(Film& film, std::uint64_t samples, std::uint64_t odd) {
    cl::CommandQueue& q = device_.queue;
    const std::size_t floats = static_cast<std::size_t>(pixel_count_) * 4;
    std::vector<float> sum(floats), squares(floats), odd_sum(floats);
    q.enqueueReadBuffer(film_sum_, CL_FALSE, 0, floats * sizeof(float), sum.data());
    q.enqueueReadBuffer(film_sum_squares_, CL_FALSE, 0, floats * sizeof(float), squares.data());
    q.enqueueReadBuffer(film_odd_sum_, CL_TRUE, 0, floats * sizeof(float), odd_sum.data());
    const cl_float4 zero4{};
    for (cl::Buffer* b : {&film_sum_, &film_sum_squares_, &film_odd_sum_})
        q.enqueueFillBuffer(*b, zero4, 0, floats * sizeof(float));
    film.add_batch(sum, squares, odd_sum, samples, odd);
}

void WavefrontIntegrator::render(std::uint32_t first_sample, std::uint32_t count, Film& film,
                                 const std::function<void(std::uint32_t)>& on_wave) {
    auto start = std::chrono::steady_clock::now();
    std::uint64_t batch = 0, batch_odd = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
        std::uint32_t sample = first_sample + i;
        run_wave(sample);
        ++batch;
        batch_odd += sample & 1u;
        if (batch == kWavesPerFlush || i + 1 == count) {
            flush_film(film, batch, batch_odd);
            batch = batch_odd = 0;
        }
        if (on_wave)
            on_wave(i + 1);
    }
    std::array<cl_uint, WP_COUNTER_COUNT> counters{};
    device_.queue.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(counters), counters.data());
    stats_.capped_paths = counters[WP_COUNTER_CAPPED];
    stats_.nonfinite_samples = counters[WP_COUNTER_NONFINITE];
    stats_.render_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace wp
