// Multiple importance sampling at every non-delta vertex (kernels/bsdf.h,
// WP_MIS_EVERY_VERTEX; docs/lights-and-camera.md, "Multiple importance
// sampling at every vertex"), end to end: the hexroom under the default
// --mis power against next-event estimation alone (--mis light, the
// estimator of before, which the golden image hexroom-mis-light pins),
// block by block. Both are unbiased only if the two weights of every path
// sum to 1: at the diffuse vertices, and where a path reaches the light by
// way of the mirror wall or the mirror sphere, whose mirrored light samples
// (--mirror-nee) are weighed against the same BSDF samples. Tolerances are
// five combined standard errors, from the films' own sample variance.
#include <catch2/catch.hpp>

#include <algorithm>

#include "render/planar_mirrors.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

TEST_CASE("MIS at every vertex: the hexroom with --mis power and --mis light agrees within noise, "
          "block by block",
          "[mis][statistical]") {
    Scene scene = test::hexroom(32, 32);
    REQUIRE(find_planar_mirrors(scene).size() == 1); // the mirror wall
    IntegratorOptions options;
    options.sampler = Sampler::Independent; // an honest error bar from the sample variance
    options.mirror_next_event = true;
    options.mis = MisStrategy::Power;
    test::Rendered power = test::render(scene, 256, 3, 0, options);
    options.mis = MisStrategy::LightOnly;
    test::Rendered light = test::render(scene, 256, 4, 0, options);
    CHECK(power.stats.nonfinite_samples == 0);
    CHECK(light.stats.nonfinite_samples == 0);
    const double kSigmas = 5.0;
    const test::BlockComparison blocks = test::compare_blocks(power.film, light.film, 8, kSigmas);
    for (int ch = 0; ch < 3; ++ch) {
        const test::MeanWithError a = test::image_mean(power.film, ch),
                                  b = test::image_mean(light.film, ch);
        INFO("channel " << ch << ": power " << a.mean << " +- " << a.standard_error << ", light "
                        << b.mean << " +- " << b.standard_error);
        CHECK(test::sigmas_apart(a, b) < kSigmas);
        CHECK(a.standard_error < 0.01 * a.mean); // the test has power
    }
    INFO("largest block deviation " << blocks.worst_sigmas << " combined sigma, "
                                    << blocks.worst_where);
    CHECK(blocks.outside == 0);
}
