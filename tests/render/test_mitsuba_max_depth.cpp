// Mitsuba's max_depth (DepthRule::PathLength, kernels/shade.cl): a Mitsuba
// file's max_depth M renders paths of at most M edges, the camera ray
// included, as Mitsuba's path integrator does (docs/mitsuba-import.md,
// "max_depth"). Its agreement with Mitsuba's own renders at M = 2 and 3 is in
// test_mitsuba_agreement.cpp, the launch plans' in test_launch_plans.cpp;
// here M = 1, where the image is known exactly, what one edge more adds,
// and rr_depth.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "support/render_helpers.hpp"

using namespace wp;
using namespace wp::test;

namespace {

// A light of radiance 12 seen by the camera, a mirror, a rough conductor
// sphere and a diffuse floor and wall, under a box filter.
Scene max_depth_scene(int max_depth) {
    SceneReadOptions read;
    read.defines = {{"max_depth", std::to_string(max_depth)}};
    return load_scene(WAVEPATH_SOURCE_DIR "/tests/data/mitsuba/max-depth.xml", read);
}

// `spp` samples, one per render call: each of the device's float32 film
// batches then holds one sample per pixel, so that a pixel's sum is the same
// sum of the same samples whatever the paths' lengths
// (tests/render/test_launch_plans.cpp).
Image one_sample_per_call(const Scene& scene, std::uint32_t spp, std::uint32_t seed) {
    IntegratorOptions options;
    options.seed = seed;
    WavefrontIntegrator integrator(device(), scene, options);
    Film film(scene.camera.width, scene.camera.height);
    for (std::uint32_t sample = 0; sample < spp; ++sample)
        integrator.render(sample, 1, film);
    return film.mean();
}

} // namespace

TEST_CASE("Mitsuba max_depth 1: the image is the emitters the camera sees, and nothing else",
          "[render][mitsuba]") {
    constexpr std::uint32_t spp = 16;
    const Rendered one = render(max_depth_scene(1), spp, 4);
    CHECK(one.stats.bounce_rays == 0);
    CHECK(one.stats.shadow_rays == 0);
    CHECK(one.stats.capped_paths == 0); // Mitsuba's limit is no cut path
    // Under a box filter each sample adds the light's 12 or nothing: every
    // pixel is 12 k / 16 for a whole k (exact in float32).
    const Image mean = one.film.mean();
    std::size_t lit = 0, whole = 0;
    for (std::size_t i = 0; i < mean.rgb.size(); ++i) {
        const double k = mean.rgb[i] * spp / 12.0;
        INFO("value " << i << ": " << mean.rgb[i]);
        REQUIRE(k == std::round(k));
        lit += mean.rgb[i] > 0.0f ? 1 : 0;
        whole += mean.rgb[i] == 12.0f ? 1 : 0;
    }
    CHECK(whole > 0);
    CHECK(lit < mean.rgb.size() / 10); // the floor, the wall and the sphere are black
    // And bit for bit the light of the camera path type alone in the
    // unlimited render (the same camera rays: the random numbers are a
    // function of the pixel, the sample and the depth).
    IntegratorOptions camera;
    camera.path_types = 1u << WP_PATH_TYPE_CAMERA;
    const Rendered seen = render(max_depth_scene(-1), spp, 4, 0, camera);
    CHECK(seen.film.mean().rgb == mean.rgb);
}

TEST_CASE("Mitsuba max_depth: one edge more adds light to every sample, and cuts no path",
          "[render][mitsuba]") {
    // The random numbers are a function of (seed, pixel, sample, depth,
    // dimension), so the paths of M + 1 are those of M up to their last
    // vertex, where M + 1 goes on: every sample, and so every pixel (sums of
    // the same number of samples, each no smaller), is at least M's, and the
    // image is brighter. No path is counted as cut by wavepath's safety cap.
    // (Rendered one sample per call: with several, which samples share a
    // float32 batch depends on how long the paths are, and the sums may
    // round the other way.)
    Image last = one_sample_per_call(max_depth_scene(1), 16, 9);
    for (int max_depth : {2, 3, 4}) {
        INFO("max_depth " << max_depth);
        CHECK(render(max_depth_scene(max_depth), 4, 9).stats.capped_paths == 0);
        const Image mean = one_sample_per_call(max_depth_scene(max_depth), 16, 9);
        std::size_t smaller = 0;
        double sum = 0.0, last_sum = 0.0;
        for (std::size_t i = 0; i < mean.rgb.size(); ++i) {
            smaller += mean.rgb[i] < last.rgb[i] ? 1 : 0;
            sum += mean.rgb[i];
            last_sum += last.rgb[i];
        }
        CHECK(smaller == 0);
        CHECK(sum > last_sum);
        last = mean;
    }
}

TEST_CASE("Mitsuba rr_depth: a file's is the roulette depth the render uses", "[render][mitsuba]") {
    // rr_depth counts as --roulette-depth does (Mitsuba 3's roulette runs
    // once depth + 1 >= rr_depth after the bounce at `depth`, wavepath's
    // once depth + 1 >= roulette_depth): the scene's gives the image of the
    // option's, bit for bit, and not the default's. The reading is tested
    // in tests/scene/test_mitsuba_import.cpp.
    Scene scene = max_depth_scene(-1);
    const Image roulette_from_1 = render(scene, 4, 3).film.mean();
    IntegratorOptions option;
    option.roulette_depth = 4;
    const Image from_option = render(scene, 4, 3, 0, option).film.mean();
    scene.rr_depth = 4;
    const Image from_file = render(scene, 4, 3).film.mean();
    CHECK(from_file.rgb == from_option.rgb);
    CHECK(from_file.rgb != roulette_from_1.rgb);
}
