// The two roulette rules (--roulette, kernels/estimator.h) are both unbiased:
// on a small showcase (smooth and rough glass, metals, plastics, textures, an
// environment map and an area light) their images agree in the whole-image
// mean and in 4x4-pixel block means within 5 combined standard errors, with
// roulette from the first bounce and from the fifth.
#include <catch2/catch.hpp>

#include <string>

#include "render/integrator_options.hpp"
#include "scene/load.hpp"
#include "support/render_helpers.hpp"

using namespace wp;
using namespace wp::test;

TEST_CASE("roulette rule: Mitsuba's rule and the default estimate the same image",
          "[render][roulette][statistical]") {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/materials/showcase.json");
    scene.camera.width = 24;
    scene.camera.height = 16;
    for (const std::uint32_t depth : {1u, 5u}) {
        IntegratorOptions throughput_rule, mitsuba_rule;
        throughput_rule.roulette_depth = mitsuba_rule.roulette_depth = depth;
        mitsuba_rule.roulette_rule = RouletteRule::Mitsuba;
        const Rendered a = render(scene, 256, 3, 0, throughput_rule);
        const Rendered b = render(scene, 256, 4, 0, mitsuba_rule);
        CHECK(a.stats.nonfinite_samples == 0);
        CHECK(b.stats.nonfinite_samples == 0);
        for (int c = 0; c < 3; ++c) {
            const MeanWithError ma = image_mean(a.film, c), mb = image_mean(b.film, c);
            INFO("roulette from " << depth << ", channel " << c << ": default " << ma.mean << " +- "
                                  << ma.standard_error << ", Mitsuba's rule " << mb.mean << " +- "
                                  << mb.standard_error);
            CHECK(sigmas_apart(ma, mb) < 5.0);
        }
        const BlockComparison blocks = compare_blocks(a.film, b.film, 4);
        INFO("roulette from " << depth << ": " << blocks.outside << " of " << blocks.blocks
                              << " block means more than 5 sigma apart, the worst "
                              << blocks.worst_where);
        CHECK(blocks.outside == 0);
    }
}
