// Stage 1, generate: camera rays against a double-precision pinhole model built
// from the scene's Camera fields, with the jitter the host draws from rng.h.
#include "cl_test_util.hpp"
#include "render/device_scene.hpp"
#include "rng.h"

#include <cmath>
#include <vector>

using namespace wp::test;

namespace {

struct GenerateResult {
    std::vector<cl_float4> origin, direction, throughput, radiance;
    std::vector<cl_uint> pixel, depth, flags, queue;
};

// Runs generate into buffers of `slots` entries that start out filled with
// sentinels (slots beyond the frame's pixels must keep them).
GenerateResult run_generate(const WpFrame& frame, std::size_t slots) {
    const cl_float4 sentinel4 = float4(-7.0f, -7.0f, -7.0f, -7.0f);
    const cl_uint sentinel = 0xa5a5a5a5u;
    cl::Buffer origin = upload(std::vector<cl_float4>(slots, sentinel4));
    cl::Buffer direction = upload(std::vector<cl_float4>(slots, sentinel4));
    cl::Buffer throughput = upload(std::vector<cl_float4>(slots, sentinel4));
    cl::Buffer radiance = upload(std::vector<cl_float4>(slots, sentinel4));
    cl::Buffer pixel = upload(std::vector<cl_uint>(slots, sentinel));
    cl::Buffer depth = upload(std::vector<cl_uint>(slots, sentinel));
    cl::Buffer flags = upload(std::vector<cl_uint>(slots, sentinel));
    cl::Buffer queue = upload(std::vector<cl_uint>(slots, sentinel));
    cl::Kernel kernel = wavefront_kernel("generate");
    set_args(kernel, frame, origin, direction, throughput, radiance, pixel, depth, flags, queue);
    launch(kernel, static_cast<std::size_t>(frame.width) * frame.height);
    return {download<cl_float4>(origin, slots),     download<cl_float4>(direction, slots),
            download<cl_float4>(throughput, slots), download<cl_float4>(radiance, slots),
            download<cl_uint>(pixel, slots),        download<cl_uint>(depth, slots),
            download<cl_uint>(flags, slots),        download<cl_uint>(queue, slots)};
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

} // namespace

TEST_CASE("generate: camera rays match a double-precision pinhole model", "[cl][generate]") {
    const int width = 7, height = 5;
    wp::Scene scene = camera_scene(width, height);
    wp::DeviceScene flat = wp::flatten_scene(scene);

    // The reference camera, from the Camera fields alone.
    const wp::Camera& c = scene.camera;
    D3 eye(c.eye.x, c.eye.y, c.eye.z);
    D3 forward = normalize(D3(c.look_at.x, c.look_at.y, c.look_at.z) - eye);
    D3 right = normalize(cross(forward, D3(c.up.x, c.up.y, c.up.z)));
    D3 up = cross(right, forward);
    const double tan_half = std::tan(0.5 * c.vertical_fov_degrees * M_PI / 180.0);
    const double aspect = double(width) / double(height);

    const std::size_t pixels = width * height, slots = round_up(pixels) + 3;
    for (cl_uint sample_index : {0u, 5u}) {
        for (cl_uint seed : {0u, 987654321u}) {
            WpFrame frame{};
            frame.camera = flat.camera;
            frame.width = width;
            frame.height = height;
            frame.seed = seed;
            frame.sample_index = sample_index;
            GenerateResult r = run_generate(frame, slots);

            double worst_direction = 0.0;
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const cl_uint pixel = cl_uint(y * width + x);
                    INFO("pixel " << x << ", " << y << " sample " << sample_index << " seed "
                                  << seed);
                    double jx = wp_random(seed, pixel, sample_index, 0u, WP_DIM_JITTER_X);
                    double jy = wp_random(seed, pixel, sample_index, 0u, WP_DIM_JITTER_Y);
                    double sx = 2.0 * (x + jx) / width - 1.0;
                    double sy = 1.0 - 2.0 * (y + jy) / height;
                    D3 expected = normalize(forward + (sx * tan_half * aspect) * right +
                                            (sy * tan_half) * up);
                    D3 got(r.direction[pixel]);
                    double error = max_abs(got - expected);
                    worst_direction = std::max(worst_direction, error);
                    CHECK(error < 1e-6);
                    CHECK(r.direction[pixel].s[3] == 0.0f);
                    CHECK(max_abs(D3(r.origin[pixel]) - eye) <= 1e-6 * max_abs(eye));

                    // Row 0 is the top of the image, column 0 its left edge.
                    if (x == 0)
                        CHECK(dot(got, right) < 0.0);
                    if (y == 0)
                        CHECK(dot(got, up) > 0.0);

                    for (int k = 0; k < 3; ++k) {
                        CHECK(r.throughput[pixel].s[k] == 1.0f);
                        CHECK(r.radiance[pixel].s[k] == 0.0f);
                    }
                    CHECK(r.radiance[pixel].s[3] == 0.0f);
                    CHECK(r.pixel[pixel] == pixel);
                    CHECK(r.depth[pixel] == 0u);
                    CHECK(r.flags[pixel] == WP_PATH_SPECULAR);
                    CHECK(r.queue[pixel] == pixel);
                }
            }
            INFO("largest direction error " << worst_direction);
            CHECK(worst_direction < 1e-6);

            // Work-items past the last pixel write nothing.
            for (std::size_t slot = pixels; slot < slots; ++slot) {
                INFO("slot " << slot);
                CHECK(r.direction[slot].s[0] == -7.0f);
                CHECK(r.origin[slot].s[0] == -7.0f);
                CHECK(r.throughput[slot].s[0] == -7.0f);
                CHECK(r.radiance[slot].s[0] == -7.0f);
                CHECK(r.pixel[slot] == 0xa5a5a5a5u);
                CHECK(r.depth[slot] == 0xa5a5a5a5u);
                CHECK(r.flags[slot] == 0xa5a5a5a5u);
                CHECK(r.queue[slot] == 0xa5a5a5a5u);
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

    const double aspect = 4.0 / 3.0;
    std::vector<std::vector<cl_float4>> waves;
    for (cl_uint sample_index = 0; sample_index < 4; ++sample_index) {
        frame.sample_index = sample_index;
        GenerateResult r = run_generate(frame, 12);
        for (int y = 0; y < 3; ++y) {
            for (int x = 0; x < 4; ++x) {
                D3 d(r.direction[y * 4 + x]);
                double sx = -d.x / d.z / aspect, sy = -d.y / d.z;
                // Film x in [-1, 1] maps to columns left to right, y to rows top to bottom.
                double column = (sx + 1.0) / 2.0 * 4.0, row = (1.0 - sy) / 2.0 * 3.0;
                INFO("pixel " << x << ", " << y << " sample " << sample_index);
                CHECK(column > x - 1e-5);
                CHECK(column < x + 1 + 1e-5);
                CHECK(row > y - 1e-5);
                CHECK(row < y + 1 + 1e-5);
            }
        }
        waves.push_back(r.direction);
    }
    // Different samples jitter differently.
    for (std::size_t pixel = 0; pixel < 12; ++pixel) {
        INFO("pixel " << pixel);
        CHECK(D3(waves[0][pixel]).x != D3(waves[1][pixel]).x);
        CHECK(D3(waves[2][pixel]).y != D3(waves[3][pixel]).y);
    }
}
