// Stage 1, generate: camera rays against a double-precision pinhole model built
// from the scene's Camera fields, with the jitter the host draws from rng.h;
// the slots' task lists (which pixel and sample each call hands out) against
// a host model built from wp_shared.h's description.
#include "render/device_scene.hpp"
#include "rng.h"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

const cl_float4 kSentinel4 = float4(-7.0f, -7.0f, -7.0f, -7.0f);
constexpr cl_uint kSentinel = 0xa5a5a5a5u;

// Everything generate writes, read back.
struct GenerateResult {
    std::vector<cl_float4> origin, direction, throughput, radiance;
    std::vector<cl_uint> task, pixel, sample, depth, flags, queue, counters;
};

// The path state of `capacity` slots on the device, kept between generate
// calls as the host keeps it between iterations. Everything but path_task
// starts out as sentinels; slots that a call does not generate must keep
// whatever they hold.
class GenerateState {
  public:
    GenerateState(std::size_t capacity, const std::vector<cl_uint>& tasks)
        : capacity_(capacity), task_(upload(tasks)),
          origin_(upload(std::vector<cl_float4>(capacity, kSentinel4))),
          direction_(upload(std::vector<cl_float4>(capacity, kSentinel4))),
          throughput_(upload(std::vector<cl_float4>(capacity, kSentinel4))),
          radiance_(upload(std::vector<cl_float4>(capacity, kSentinel4))),
          pixel_(upload(std::vector<cl_uint>(capacity, kSentinel))),
          sample_(upload(std::vector<cl_uint>(capacity, kSentinel))),
          depth_(upload(std::vector<cl_uint>(capacity, kSentinel))),
          flags_(upload(std::vector<cl_uint>(capacity, kSentinel))) {
        REQUIRE(tasks.size() == capacity);
    }

    // One generate call over slots[0, slot_count) (entries of `slots` past
    // slot_count are in the buffer but must be ignored), appending to ray
    // queue `ray_counter` whose first `queued_before` entries are already
    // taken (they hold 1000 + i). counters[ray_counter] starts at
    // queued_before and every other counter at 100 + its index; the queues
    // have room past all of them, so a kernel appending at the wrong counter
    // or to the wrong queue shows in the contents rather than writing out of
    // bounds. The launch covers every entry of `slots`. A list 0, 1, 2, ... is
    // passed as it is at the start of a wave (slot = work-item index), any
    // other through the finished queue, as regeneration does.
    GenerateResult run(const WpFrame& frame, const std::vector<cl_uint>& slots, cl_uint slot_count,
                       cl_uint ray_counter, cl_uint queued_before,
                       const std::string& options = "") {
        const std::size_t queue_size = frame.pool_size;
        std::vector<cl_uint> queues(2 * queue_size + 100 + WP_COUNTER_COUNT, kSentinel);
        const std::size_t base = ray_counter * queue_size;
        for (cl_uint i = 0; i < queued_before; ++i)
            queues[base + i] = 1000u + i;
        std::vector<cl_uint> counters(WP_COUNTER_COUNT);
        for (cl_uint i = 0; i < WP_COUNTER_COUNT; ++i)
            counters[i] = i == ray_counter ? queued_before : 100u + i;
        bool identity = true;
        for (std::size_t i = 0; i < slots.size(); ++i)
            identity = identity && slots[i] == i;
        DeviceBuffers buffers = stage_buffers(capacity_, 1);
        buffers.path_task = task_;
        buffers.ray_origin = origin_;
        buffers.ray_direction = direction_;
        buffers.throughput = throughput_;
        buffers.radiance = radiance_;
        buffers.path_pixel = pixel_;
        buffers.path_sample = sample_;
        buffers.path_depth = depth_;
        buffers.path_flags = flags_;
        buffers.finished_queue = upload(slots);
        buffers.ray_queues = upload(queues);
        buffers.counters = upload(counters);
        run_stage("generate", frame, make_launch(slot_count, ray_counter, !identity), buffers,
                  slots.size(), options);
        std::vector<cl_uint> all_queues = download<cl_uint>(buffers.ray_queues, queues.size());
        // Appending to queue B leaves queue A untouched (the test's made-up
        // survivors can make queue A run past its end, which the integrator's
        // never do); the queue appended to is read from its start.
        if (ray_counter == WP_COUNTER_QUEUE_B)
            for (std::size_t i = 0; i < queue_size; ++i)
                REQUIRE(all_queues[i] == kSentinel);
        std::vector<cl_uint> queue(all_queues.begin() + static_cast<std::ptrdiff_t>(base),
                                   all_queues.end());
        return {download<cl_float4>(origin_, capacity_),
                download<cl_float4>(direction_, capacity_),
                download<cl_float4>(throughput_, capacity_),
                download<cl_float4>(radiance_, capacity_),
                download<cl_uint>(task_, capacity_),
                download<cl_uint>(pixel_, capacity_),
                download<cl_uint>(sample_, capacity_),
                download<cl_uint>(depth_, capacity_),
                download<cl_uint>(flags_, capacity_),
                queue,
                download<cl_uint>(buffers.counters, WP_COUNTER_COUNT)};
    }

  private:
    std::size_t capacity_;
    cl::Buffer task_, origin_, direction_, throughput_, radiance_, pixel_, sample_, depth_, flags_;
};

// The slots a call appended to the ray queue, after checking the queue's
// bookkeeping: counters[ray_counter] grew by exactly the entries appended,
// the entries before them and every other counter are untouched, and the
// entry after them is still a sentinel.
std::vector<cl_uint> appended_slots(const GenerateResult& r, cl_uint ray_counter,
                                    cl_uint queued_before) {
    const cl_uint end = r.counters[ray_counter];
    REQUIRE(end >= queued_before);
    REQUIRE(end < r.queue.size());
    for (cl_uint i = 0; i < queued_before; ++i)
        CHECK(r.queue[i] == 1000u + i);
    CHECK(r.queue[end] == kSentinel);
    for (cl_uint i = 0; i < WP_COUNTER_COUNT; ++i)
        if (i != ray_counter)
            CHECK(r.counters[i] == 100u + i);
    return std::vector<cl_uint>(r.queue.begin() + queued_before, r.queue.begin() + end);
}

wp::Scene camera_scene(int width, int height) {
    wp::Scene scene;
    scene.camera.eye = {1.0, 2.0, 3.0};
    scene.camera.look_at = {0.5, 1.25, -2.0};
    scene.camera.up = {0.2, 1.0, 0.3}; // not perpendicular to the view direction
    scene.camera.vertical_fov_degrees = 52.5;
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

// The reference camera, from the Camera fields alone.
struct Pinhole {
    D3 eye, forward, right, up;
    double tan_half = 0.0, aspect = 0.0;
    int width = 0, height = 0;

    explicit Pinhole(const wp::Camera& c) : width(c.width), height(c.height) {
        eye = D3(c.eye.x, c.eye.y, c.eye.z);
        forward = normalize(D3(c.look_at.x, c.look_at.y, c.look_at.z) - eye);
        right = normalize(cross(forward, D3(c.up.x, c.up.y, c.up.z)));
        up = cross(right, forward);
        tan_half = std::tan(0.5 * c.vertical_fov_degrees * M_PI / 180.0);
        aspect = double(width) / double(height);
    }

    // The direction of `pixel`'s ray for `sample`, jittered with rng.h's numbers.
    D3 direction(cl_uint seed, cl_uint pixel, cl_uint sample) const {
        const int x = int(pixel % cl_uint(width)), y = int(pixel / cl_uint(width));
        double jx = wp_random(seed, pixel, sample, 0u, WP_DIM_JITTER_X);
        double jy = wp_random(seed, pixel, sample, 0u, WP_DIM_JITTER_Y);
        double sx = 2.0 * (x + jx) / width - 1.0;
        double sy = 1.0 - 2.0 * (y + jy) / height;
        return normalize(forward + (sx * tan_half * aspect) * right + (sy * tan_half) * up);
    }
};

// A freshly generated path in `slot`: the camera ray and the initial state.
void check_fresh_path(const GenerateResult& r, std::size_t slot, const Pinhole& camera,
                      cl_uint seed, const Task& task) {
    D3 got = from_float4(r.direction[slot]);
    CHECK(max_abs(got - camera.direction(seed, task.pixel, task.sample)) < 1e-6);
    CHECK(r.direction[slot].s[3] == 0.0f);
    CHECK(max_abs(from_float4(r.origin[slot]) - camera.eye) <= 1e-6 * max_abs(camera.eye));
    CHECK(r.origin[slot].s[3] == 0.0f);
    for (int k = 0; k < 3; ++k) {
        CHECK(r.throughput[slot].s[k] == 1.0f);
        CHECK(r.radiance[slot].s[k] == 0.0f);
    }
    CHECK(r.throughput[slot].s[3] == 1.0f); // the eta^2 crossed so far (estimator.h)
    CHECK(r.radiance[slot].s[3] == 0.0f);
    CHECK(r.pixel[slot] == task.pixel);
    CHECK(r.sample[slot] == task.sample);
    CHECK(r.depth[slot] == 0u);
    CHECK(r.flags[slot] == WP_PATH_SPECULAR);
}

// Slot `slot` holds exactly what it held in `before`.
void check_untouched(const GenerateResult& r, const GenerateResult& before, std::size_t slot) {
    for (int k = 0; k < 4; ++k) {
        CHECK(float_bits(r.origin[slot].s[k]) == float_bits(before.origin[slot].s[k]));
        CHECK(float_bits(r.direction[slot].s[k]) == float_bits(before.direction[slot].s[k]));
        CHECK(float_bits(r.throughput[slot].s[k]) == float_bits(before.throughput[slot].s[k]));
        CHECK(float_bits(r.radiance[slot].s[k]) == float_bits(before.radiance[slot].s[k]));
    }
    CHECK(r.task[slot] == before.task[slot]);
    CHECK(r.pixel[slot] == before.pixel[slot]);
    CHECK(r.sample[slot] == before.sample[slot]);
    CHECK(r.depth[slot] == before.depth[slot]);
    CHECK(r.flags[slot] == before.flags[slot]);
}

} // namespace

TEST_CASE("generate: camera rays match a double-precision pinhole model", "[cl][generate]") {
    const int width = 7, height = 5;
    wp::Scene scene = camera_scene(width, height);
    wp::DeviceScene flat = wp::flatten_scene(scene);
    const Pinhole camera(scene.camera);

    // One slot per pixel (the default pool), every slot listed once, in
    // reverse: the queue order must not matter. Two more entries past
    // slot_count name slots 0 and 1 again; as both have a second sample to
    // give, a work-item that ignored slot_count would show in their state.
    const cl_uint pixels = width * height;
    const std::size_t capacity = round_up(pixels) + 3;
    std::vector<cl_uint> list;
    for (cl_uint slot = pixels; slot-- > 0;)
        list.push_back(slot);
    list.push_back(0u);
    list.push_back(1u);

    for (cl_uint first_sample : {0u, 5u}) {
        for (cl_uint seed : {0u, 987654321u}) {
            WpFrame frame{};
            frame.camera = flat.camera;
            frame.width = width;
            frame.height = height;
            frame.seed = seed;
            frame.first_sample = first_sample;
            frame.sample_count = 2;
            frame.pool_size = pixels;
            GenerateState state(capacity, std::vector<cl_uint>(capacity, 0u));
            const cl_uint ray_counter = seed == 0 ? WP_COUNTER_QUEUE_A : WP_COUNTER_QUEUE_B;
            const cl_uint queued_before = 5; // survivors shade already pushed
            GenerateResult r = state.run(frame, list, pixels, ray_counter, queued_before);

            double worst_direction = 0.0;
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const cl_uint pixel = cl_uint(y * width + x);
                    INFO("pixel " << x << ", " << y << " sample " << first_sample << " seed "
                                  << seed);
                    D3 expected = camera.direction(seed, pixel, first_sample);
                    D3 got = from_float4(r.direction[pixel]);
                    double error = max_abs(got - expected);
                    worst_direction = std::max(worst_direction, error);
                    CHECK(error < 1e-6);
                    check_fresh_path(r, pixel, camera, seed, {pixel, first_sample});
                    CHECK(r.task[pixel] == 1u);

                    // Row 0 is the top of the image, column 0 its left edge.
                    if (x == 0)
                        CHECK(dot(got, camera.right) < 0.0);
                    if (y == 0)
                        CHECK(dot(got, camera.up) > 0.0);
                }
            }
            INFO("largest direction error " << worst_direction);
            CHECK(worst_direction < 1e-6);

            // Every slot was appended once, after the entries already queued.
            std::vector<cl_uint> queued = appended_slots(r, ray_counter, queued_before);
            std::sort(queued.begin(), queued.end());
            std::vector<cl_uint> all(pixels);
            for (cl_uint i = 0; i < pixels; ++i)
                all[i] = i;
            CHECK(queued == all);

            // Slots never listed write nothing.
            for (std::size_t slot = pixels; slot < capacity; ++slot) {
                INFO("slot " << slot);
                CHECK(r.direction[slot].s[0] == -7.0f);
                CHECK(r.origin[slot].s[0] == -7.0f);
                CHECK(r.throughput[slot].s[0] == -7.0f);
                CHECK(r.radiance[slot].s[0] == -7.0f);
                CHECK(r.task[slot] == 0u);
                CHECK(r.pixel[slot] == kSentinel);
                CHECK(r.sample[slot] == kSentinel);
                CHECK(r.depth[slot] == kSentinel);
                CHECK(r.flags[slot] == kSentinel);
            }
        }
    }
}

TEST_CASE("generate: each ray passes through its own pixel, jittered per sample",
          "[cl][generate]") {
    // A square camera looking down -z: film coordinates are read straight off the direction.
    wp::Scene scene;
    scene.camera.eye = {0.0, 0.0, 0.0};
    scene.camera.look_at = {0.0, 0.0, -1.0};
    scene.camera.up = {0.0, 1.0, 0.0};
    scene.camera.vertical_fov_degrees = 90.0; // tan(45 deg) = 1: the film spans [-1, 1]
    scene.camera.width = 4;
    scene.camera.height = 3;
    wp::DeviceScene flat = wp::flatten_scene(scene);
    WpFrame frame{};
    frame.camera = flat.camera;
    frame.width = 4;
    frame.height = 3;
    frame.seed = 42;
    frame.first_sample = 0;
    frame.sample_count = 4;
    frame.pool_size = 12;

    // Four calls over the same slots: each slot's one pixel gets samples 0, 1, 2, 3.
    std::vector<cl_uint> all(12);
    for (cl_uint i = 0; i < 12; ++i)
        all[i] = i;
    GenerateState state(12, std::vector<cl_uint>(12, 0u));
    const double aspect = 4.0 / 3.0;
    std::vector<std::vector<cl_float4>> waves;
    GenerateResult last;
    for (cl_uint sample_index = 0; sample_index < 4; ++sample_index) {
        GenerateResult r = state.run(frame, all, 12, WP_COUNTER_QUEUE_A, 0);
        CHECK(appended_slots(r, WP_COUNTER_QUEUE_A, 0).size() == 12);
        for (int y = 0; y < 3; ++y) {
            for (int x = 0; x < 4; ++x) {
                const cl_uint slot = cl_uint(y * 4 + x);
                D3 d = from_float4(r.direction[slot]);
                double sx = -d.x / d.z / aspect, sy = -d.y / d.z;
                // Film x in [-1, 1] maps to columns left to right, y to rows top to bottom.
                double column = (sx + 1.0) / 2.0 * 4.0, row = (1.0 - sy) / 2.0 * 3.0;
                INFO("pixel " << x << ", " << y << " sample " << sample_index);
                CHECK(column > x - 1e-5);
                CHECK(column < x + 1 + 1e-5);
                CHECK(row > y - 1e-5);
                CHECK(row < y + 1 + 1e-5);
                CHECK(r.pixel[slot] == slot);
                CHECK(r.sample[slot] == sample_index);
                CHECK(r.task[slot] == sample_index + 1);
            }
        }
        waves.push_back(r.direction);
        last = r;
    }
    // Different samples jitter differently.
    for (std::size_t pixel = 0; pixel < 12; ++pixel) {
        INFO("pixel " << pixel);
        CHECK(from_float4(waves[0][pixel]).x != from_float4(waves[1][pixel]).x);
        CHECK(from_float4(waves[2][pixel]).y != from_float4(waves[3][pixel]).y);
    }

    // A fifth call: every slot has given its four samples, so none is queued
    // and the finished paths' state (read by accumulate) stays as it was.
    GenerateResult r = state.run(frame, all, 12, WP_COUNTER_QUEUE_B, 3);
    CHECK(appended_slots(r, WP_COUNTER_QUEUE_B, 3).empty());
    for (std::size_t slot = 0; slot < 12; ++slot) {
        INFO("slot " << slot);
        check_untouched(r, last, slot);
    }
}

TEST_CASE("generate: a pool smaller than the image hands out every (pixel, sample) once, "
          "sample-major",
          "[cl][generate]") {
    const int width = 7, height = 5;
    const cl_uint pixels = width * height;
    wp::Scene scene = camera_scene(width, height);
    wp::DeviceScene flat = wp::flatten_scene(scene);
    const Pinhole camera(scene.camera);

    // 8: slots own 5 or 4 pixels; 1: one slot owns them all; 34: slot 0 owns
    // two pixels and the others one; 35: one pixel each.
    for (cl_uint pool : {8u, 1u, 34u, 35u}) {
        WpFrame frame{};
        frame.camera = flat.camera;
        frame.width = width;
        frame.height = height;
        frame.seed = 321;
        frame.first_sample = 6;
        frame.sample_count = 3;
        frame.pool_size = pool;
        INFO("pool " << pool);

        // Each slot's task list from the host model, and a check of the model
        // itself: together the lists cover every (pixel, sample) once.
        std::vector<std::vector<Task>> tasks(pool);
        std::vector<Task> every;
        for (cl_uint slot = 0; slot < pool; ++slot) {
            tasks[slot] = slot_tasks(frame, slot);
            every.insert(every.end(), tasks[slot].begin(), tasks[slot].end());
        }
        std::sort(every.begin(), every.end());
        REQUIRE(every.size() == std::size_t(pixels) * frame.sample_count);
        REQUIRE(std::adjacent_find(every.begin(), every.end()) == every.end());

        // Two slots past the pool that are never listed.
        const std::size_t capacity = pool + 2;
        GenerateState state(capacity, std::vector<cl_uint>(capacity, 0u));
        GenerateResult before = state.run(frame, {}, 0, WP_COUNTER_QUEUE_A, 0);
        CHECK(appended_slots(before, WP_COUNTER_QUEUE_A, 0).empty());

        // Each call lists a random subset of the pool in random order, as the
        // finished queue does with regeneration; the rest of the pool follows
        // past slot_count and must be ignored.
        std::mt19937 generator(pool);
        std::vector<std::size_t> done(pool, 0);
        std::vector<Task> generated;
        std::map<cl_uint, cl_uint> last_sample; // per pixel: samples arrive in order
        int calls = 0;
        auto call = [&](std::vector<cl_uint> listed, const std::vector<cl_uint>& unlisted) {
            std::shuffle(listed.begin(), listed.end(), generator);
            const auto slot_count = cl_uint(listed.size());
            std::vector<cl_uint> list = listed;
            list.insert(list.end(), unlisted.begin(), unlisted.end());
            const cl_uint ray_counter = calls % 2 ? WP_COUNTER_QUEUE_B : WP_COUNTER_QUEUE_A;
            const cl_uint queued_before = cl_uint(generator() % 4);
            GenerateResult r = state.run(frame, list, slot_count, ray_counter, queued_before);
            INFO("call " << calls << ": " << slot_count << " slots listed");
            ++calls;

            std::vector<cl_uint> expected_queue;
            for (cl_uint slot : listed)
                if (done[slot] < tasks[slot].size())
                    expected_queue.push_back(slot);
            std::vector<cl_uint> queued = appended_slots(r, ray_counter, queued_before);
            std::sort(queued.begin(), queued.end());
            std::sort(expected_queue.begin(), expected_queue.end());
            // Exactly the listed slots with tasks left, each once; retired
            // and unlisted slots are not queued.
            CHECK(queued == expected_queue);

            for (cl_uint slot = 0; slot < capacity; ++slot) {
                INFO("slot " << slot);
                const bool advances =
                    std::binary_search(expected_queue.begin(), expected_queue.end(), slot);
                if (!advances) {
                    check_untouched(r, before, slot);
                    continue;
                }
                const Task& task = tasks[slot][done[slot]];
                INFO("task " << done[slot] << ": pixel " << task.pixel << " sample "
                             << task.sample);
                ++done[slot];
                CHECK(r.task[slot] == done[slot]);
                // The jitter comes from this task's sample, not from first_sample.
                check_fresh_path(r, slot, camera, frame.seed, task);
                CHECK(r.pixel[slot] % pool == slot);
                auto previous = last_sample.find(task.pixel);
                if (previous != last_sample.end())
                    CHECK(task.sample == previous->second + 1);
                else
                    CHECK(task.sample == frame.first_sample);
                last_sample[task.pixel] = task.sample;
                generated.push_back({r.pixel[slot], r.sample[slot]});
            }
            before = r;
        };
        auto all_done = [&] {
            for (cl_uint slot = 0; slot < pool; ++slot)
                if (done[slot] < tasks[slot].size())
                    return false;
            return true;
        };
        while (!all_done()) {
            REQUIRE(calls < 1000);
            std::vector<cl_uint> listed, unlisted;
            for (cl_uint slot = 0; slot < pool; ++slot)
                (generator() % 10 < 7 ? listed : unlisted).push_back(slot);
            call(listed, unlisted);
        }
        // Once more with every slot listed: all are retired, none is queued.
        std::vector<cl_uint> everyone(pool);
        for (cl_uint slot = 0; slot < pool; ++slot)
            everyone[slot] = slot;
        const std::size_t count_before = generated.size();
        call(everyone, {});
        CHECK(generated.size() == count_before);

        // Every (pixel, sample) pair exactly once, and every slot retired.
        std::sort(generated.begin(), generated.end());
        CHECK(generated == every);
        for (cl_uint slot = 0; slot < pool; ++slot)
            CHECK(done[slot] == tasks[slot].size());
        CHECK(last_sample.size() == pixels);
    }
}

// A slot's task counter is 32 bits, so the host never asks for more than
// 2^32 - 1 tasks per slot in one call (WavefrontIntegrator::render splits
// larger calls; with a pool of 16 on a 4096 x 4096 image, 4096 samples would
// be exactly 2^32 tasks and wrap to 0, leaving the image black). At the
// largest call it makes, the first task still starts.
TEST_CASE("generate: a slot with nearly 2^32 tasks still starts its first task", "[cl][generate]") {
    WpFrame frame{};
    frame.camera = wp::flatten_scene(camera_scene(4096, 4096)).camera;
    frame.width = 4096;
    frame.height = 4096;
    frame.seed = 5;
    frame.first_sample = 0;
    frame.sample_count = 4095; // 2^20 pixels x 4095 samples = 2^32 - 2^20 tasks
    frame.pool_size = 16;
    GenerateState state(16, std::vector<cl_uint>(16, 0u));
    GenerateResult r = state.run(frame, {0u}, 1, WP_COUNTER_QUEUE_A, 0);
    INFO("slot 0 owns 2^20 pixels x 4095 samples");
    CHECK(appended_slots(r, WP_COUNTER_QUEUE_A, 0) == std::vector<cl_uint>{0u});
    CHECK(r.task[0] == 1u);
    CHECK(r.pixel[0] == 0u);
    CHECK(r.sample[0] == 0u);
}

namespace {

// Shirley and Chiu's concentric map in double precision, written from the
// paper's description (not from kernels/sampling.h).
std::pair<double, double> concentric_disk(double u1, double u2) {
    const double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
    if (a == 0.0 && b == 0.0)
        return {0.0, 0.0};
    double r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = (M_PI / 4.0) * (b / a);
    } else {
        r = b;
        phi = M_PI / 2.0 - (M_PI / 4.0) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

} // namespace

TEST_CASE("generate: a thin lens's rays leave the aperture disk and meet the pinhole ray on the "
          "plane of focus",
          "[cl][generate][camera]") {
    const int width = 7, height = 5;
    wp::Scene scene = camera_scene(width, height);
    scene.camera.aperture_radius = 0.3;
    scene.camera.focus_distance = 2.5;
    wp::DeviceScene flat = wp::flatten_scene(scene);
    const Pinhole camera(scene.camera);
    const cl_uint pixels = width * height;
    std::vector<cl_uint> list(pixels);
    for (cl_uint i = 0; i < pixels; ++i)
        list[i] = i;

    // The lens is compiled in by the general kernels (and by
    // -D WP_HAS_LENS=1 alone); its feature says so.
    CHECK(wp::analyse_features(scene).lens);
    WpFrame frame{};
    frame.camera = flat.camera;
    frame.width = width;
    frame.height = height;
    frame.seed = 77;
    frame.sample_count = 1;
    frame.pool_size = pixels;
    GenerateState state(pixels, std::vector<cl_uint>(pixels, 0u));
    GenerateResult r = state.run(frame, list, pixels, WP_COUNTER_QUEUE_A, 0);

    double worst_origin = 0.0, worst_focus = 0.0;
    for (cl_uint pixel = 0; pixel < pixels; ++pixel) {
        INFO("pixel " << pixel);
        // The pinhole ray's direction scaled to unit length along forward,
        // and where it meets the plane of focus.
        const D3 d = camera.direction(frame.seed, pixel, 0);
        const D3 focus_point =
            camera.eye + (scene.camera.focus_distance / dot(d, camera.forward)) * d;
        const auto [lx, ly] =
            concentric_disk(wp_random(frame.seed, pixel, 0, WP_LENS_BOUNCE, WP_DIM_LENS_U),
                            wp_random(frame.seed, pixel, 0, WP_LENS_BOUNCE, WP_DIM_LENS_V));
        const D3 aperture_point =
            camera.eye + scene.camera.aperture_radius * (lx * camera.right + ly * camera.up);

        const D3 origin = from_float4(r.origin[pixel]);
        const D3 direction = from_float4(r.direction[pixel]);
        worst_origin = std::max(worst_origin, max_abs(origin - aperture_point));
        CHECK(max_abs(origin - aperture_point) < 1e-6 * (1.0 + max_abs(camera.eye)));
        // On the aperture: in the plane of the eye, within the radius.
        CHECK(std::fabs(dot(origin - camera.eye, camera.forward)) < 1e-6);
        CHECK(length(origin - camera.eye) <= scene.camera.aperture_radius * (1.0 + 1e-6));
        // The ray passes through the focus point: its distance from the line.
        const D3 to_focus = focus_point - origin;
        const double miss = length(to_focus - dot(to_focus, direction) * direction);
        worst_focus = std::max(worst_focus, miss);
        CHECK(miss < 1e-5 * length(to_focus));
        CHECK(std::fabs(length(direction) - 1.0) < 1e-6);
    }
    INFO("largest origin error " << worst_origin << ", largest miss of the focus point "
                                 << worst_focus);
    CHECK(worst_focus < 1e-5 * scene.camera.focus_distance);

    // Aperture 0 is the pinhole, bit for bit, in kernels that have the lens
    // compiled in (the general ones) and in those that do not.
    wp::Scene pinhole_scene = camera_scene(width, height);
    WpFrame pinhole = frame;
    pinhole.camera = wp::flatten_scene(pinhole_scene).camera;
    CHECK(pinhole.camera.lens_up.s[3] == 0.0f);
    GenerateState with_lens(pixels, std::vector<cl_uint>(pixels, 0u));
    GenerateResult a = with_lens.run(pinhole, list, pixels, WP_COUNTER_QUEUE_A, 0);
    GenerateState without_lens(pixels, std::vector<cl_uint>(pixels, 0u));
    GenerateResult b =
        without_lens.run(pinhole, list, pixels, WP_COUNTER_QUEUE_A, 0,
                         "-D WP_HAS_LENS=0 -D WP_HAS_TENT_FILTER=0 -D WP_HAS_GAUSSIAN_FILTER=0");
    for (cl_uint pixel = 0; pixel < pixels; ++pixel)
        for (int k = 0; k < 4; ++k) {
            CHECK(float_bits(a.origin[pixel].s[k]) == float_bits(b.origin[pixel].s[k]));
            CHECK(float_bits(a.direction[pixel].s[k]) == float_bits(b.direction[pixel].s[k]));
        }
}
