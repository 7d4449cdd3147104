// End-to-end renders of the reference scene at low resolution.
#include <catch2/catch.hpp>

#include <cmath>

#include "scene/load.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

Scene small_hexroom(int size) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/hexroom.json");
    scene.camera.width = size;
    scene.camera.height = size;
    return scene;
}

} // namespace

TEST_CASE("hexroom: no NaN or Inf, and no path reaches the depth cap") {
    test::Rendered r = test::render(small_hexroom(32), 16);
    CHECK(r.stats.nonfinite_samples == 0);
    CHECK(r.stats.capped_paths == 0);
    for (float v : r.film.mean().rgb)
        REQUIRE(std::isfinite(v));
    CHECK(r.stats.camera_rays == 32u * 32u * 16u);
}

TEST_CASE("hexroom: the same seed renders bit-identically twice") {
    Scene scene = small_hexroom(24);
    Image a = test::render(scene, 8, 7).film.mean();
    Image b = test::render(scene, 8, 7).film.mean();
    CHECK(a.rgb == b.rgb);
}

TEST_CASE("hexroom: renders with different seeds agree within noise", "[statistical]") {
    Scene scene = small_hexroom(24);
    test::Rendered a = test::render(scene, 64, 1);
    test::Rendered b = test::render(scene, 64, 2);
    Image ia = a.film.mean(), ib = b.film.mean();
    CHECK(ia.rgb != ib.rgb); // the seed matters
    for (int c = 0; c < 3; ++c) {
        test::MeanWithError ma = test::image_mean(a.film, c), mb = test::image_mean(b.film, c);
        double sigma = std::hypot(ma.standard_error, mb.standard_error);
        INFO("channel " << c << ": " << ma.mean << " vs " << mb.mean << ", sigma " << sigma);
        CHECK(std::abs(ma.mean - mb.mean) < 5.0 * sigma);
    }
}

TEST_CASE("hexroom: splitting the samples between two renders gives the same film") {
    // Counter-based random numbers: samples [0, 8) in one go equal [0, 4) + [4, 8).
    // The stratified sampler too: its numbers are as pure a function of the key.
    Scene scene = small_hexroom(16);
    for (Sampler sampler : {Sampler::Independent, Sampler::Sobol}) {
        INFO("sampler " << to_string(sampler));
        IntegratorOptions options;
        options.seed = 3;
        options.sampler = sampler;
        Film whole = test::render(scene, 8, 3, 0, options).film;
        Film split = test::render(scene, 4, 3, 0, options).film;
        split.merge(test::render(scene, 4, 3, 4, options).film);
        Image a = whole.mean(), b = split.mean();
        REQUIRE(a.rgb.size() == b.rgb.size());
        for (std::size_t i = 0; i < a.rgb.size(); ++i)
            REQUIRE(a.rgb[i] == Approx(b.rgb[i]).epsilon(1e-5).margin(1e-6));
    }
}
