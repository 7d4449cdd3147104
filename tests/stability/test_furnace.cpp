// Case 8, near-white furnace: a closed box whose walls all have albedo 0.99 and
// emit Le = 1 converges to Le / (1 - 0.99) = 100 everywhere. Paths average 100
// bounces; Russian roulette (survival = throughput, divided out) keeps the
// estimate unbiased, and the depth cap (1024) cuts about 0.99^1024 = 3.4e-5 of
// the paths; each cut path loses on average the 100 Le it would still have
// gathered, a relative bias of about 3.4e-5, far below the noise.
// The naive failure is a small fixed depth limit: cutting at 64 bounces gives
// (1 - 0.99^65) / (1 - 0.99) = 48 instead of 100.
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

constexpr double kExpected = 1.0 / (1.0 - 0.99);

} // namespace

TEST_CASE("furnace 0.99: every pixel converges to 100 Le (next-event estimation off)",
          "[stability][furnace][statistical]") {
    // Without next-event estimation a sample is Le times the number of
    // surfaces the path met (roulette keeps the throughput at 1): bounded
    // variance, so each pixel can be held to 5 of its own standard errors.
    // (With it, uniform area sampling has unbounded variance next to the
    // box's edges; see the analytic furnace test in tests/render.)
    Scene scene = stress_scene("furnace-099", 16);
    IntegratorOptions options;
    options.next_event_estimation = false;
    auto start = std::chrono::steady_clock::now();
    test::Rendered r = test::render(scene, 128, 5, 0, options);
    double seconds = seconds_since(start);
    Image mean = r.film.mean();
    Image variance = r.film.variance_of_mean();
    int outside = 0;
    double worst = 0.0, largest_sigma = 0.0, total = 0.0;
    for (std::size_t i = 0; i < mean.rgb.size(); ++i) {
        double sigma = std::sqrt(static_cast<double>(variance.rgb[i]));
        double d = std::abs(mean.rgb[i] - kExpected);
        worst = std::max(worst, d / sigma);
        largest_sigma = std::max(largest_sigma, sigma / kExpected);
        total += mean.rgb[i];
        if (d > kSigmas * sigma)
            ++outside;
    }
    test::MeanWithError m = test::image_mean(r.film, 0);
    WARN("furnace 0.99, no NEE, 16x16 x 128 spp: image mean "
         << m.mean << " +- " << m.standard_error << " (expected " << kExpected << "), worst pixel "
         << worst << " sigma, largest "
         << "relative sigma " << largest_sigma << ", " << r.stats.capped_paths << " paths cut, "
         << seconds << " s");
    CHECK(outside == 0);
    CHECK(std::abs(m.mean - kExpected) < kSigmas * m.standard_error);
    // The test has power: a sample's sigma is 99.5 % of the mean, so 128
    // samples give about 9 % per pixel (and 0.55 % on the image mean).
    CHECK(largest_sigma < 0.15);
    CHECK(all_finite(r));
}

TEST_CASE("furnace 0.99: the image mean converges to 100 Le with next-event estimation",
          "[stability][furnace][statistical]") {
    Scene scene = stress_scene("furnace-099", 32);
    auto start = std::chrono::steady_clock::now();
    test::Rendered r = test::render(scene, 32, 6);
    double seconds = seconds_since(start);
    for (int c = 0; c < 3; ++c) {
        test::MeanWithError m = test::image_mean(r.film, c);
        INFO("channel " << c << ": " << m.mean << " +- " << m.standard_error);
        CHECK(std::abs(m.mean - kExpected) < kSigmas * m.standard_error);
        CHECK(m.standard_error < 0.01 * kExpected);
    }
    WARN("furnace 0.99 with NEE, 32x32 x 32 spp: image mean "
         << test::image_mean(r.film, 0).mean << " +- " << test::image_mean(r.film, 0).standard_error
         << ", " << r.stats.capped_paths << " paths cut, " << seconds << " s");
    CHECK(all_finite(r));
}

TEST_CASE("furnace 0.99: a naive fixed depth limit is far off (what the cap must not be)",
          "[stability][furnace][statistical]") {
    Scene scene = stress_scene("furnace-099", 8);
    IntegratorOptions options;
    options.next_event_estimation = false;
    options.max_depth = 64;
    test::Rendered r = test::render(scene, 64, 5, 0, options);
    test::MeanWithError m = test::image_mean(r.film, 0);
    // Each of the 65 surfaces a path can meet adds Le with probability 0.99^k.
    const double truncated = (1.0 - std::pow(0.99, 65)) / (1.0 - 0.99);
    WARN("furnace 0.99 cut at 64 bounces: " << m.mean << " +- " << m.standard_error
                                            << " (truncated series " << truncated << ")");
    CHECK(std::abs(m.mean - kExpected) > 20.0 * m.standard_error);
    CHECK(std::abs(m.mean - truncated) < kSigmas * m.standard_error);
    CHECK(r.stats.capped_paths > 0);
}
