// Cases 1 and 2, scale and distance from the origin: the hexroom scaled by
// 1e-4 .. 1e4 and translated by (1e4, -1e4, 1e4) must render like the
// original within noise with the same seed. Compared block by block (4 x 4
// blocks of 6 x 6 pixels, per channel) and as whole-image means, each in units
// of the two renders' combined standard error. A fixed epsilon (the naive
// variant, docs/stability.md) fails this at both ends of the series.
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

constexpr int kSize = 24;
constexpr int kBlock = 6;
constexpr std::uint32_t kSpp = 256;
constexpr std::uint32_t kSeed = 11;

const test::Rendered& reference() {
    static const test::Rendered r = test::render(hexroom(kSize), kSpp, kSeed);
    return r;
}

void check_like_hexroom(const std::string& name) {
    const test::Rendered& ref = reference();
    auto start = std::chrono::steady_clock::now();
    test::Rendered r = test::render(stress_scene(name, kSize), kSpp, kSeed);
    double seconds = seconds_since(start);
    BlockComparison blocks = compare_blocks(r.film, ref.film, kBlock);
    double worst_mean = 0.0;
    for (int c = 0; c < 3; ++c)
        worst_mean = std::max(worst_mean, image_mean_sigmas(r.film, ref.film, c));
    WARN(name << ": blocks worst " << blocks.worst_sigmas << " sigma (" << blocks.worst_where
              << "), mean " << blocks.mean_sigmas << " sigma, " << blocks.outside << "/"
              << blocks.blocks << " over 5; image means worst " << worst_mean << " sigma; "
              << r.stats.nonfinite_samples << " non-finite, " << r.stats.capped_paths << " capped; "
              << seconds << " s");
    CHECK(blocks.outside == 0);
    CHECK(worst_mean < kSigmas);
    CHECK(blocks.largest_relative_sigma < 0.15); // the comparison has power
    CHECK(all_finite(r));
}

} // namespace

TEST_CASE("scale: the hexroom scaled by 1e-4 renders like the original", "[stability][scale]") {
    check_like_hexroom("scale-1e-4");
}

TEST_CASE("scale: the hexroom scaled by 1e-2 renders like the original", "[stability][scale]") {
    check_like_hexroom("scale-1e-2");
}

TEST_CASE("scale: the hexroom scaled by 1e2 renders like the original", "[stability][scale]") {
    check_like_hexroom("scale-1e+2");
}

TEST_CASE("scale: the hexroom scaled by 1e4 renders like the original", "[stability][scale]") {
    check_like_hexroom("scale-1e+4");
}

TEST_CASE("far from the origin: the hexroom translated by 1e4 renders like the original",
          "[stability][translate]") {
    check_like_hexroom("translate-1e4");
}
