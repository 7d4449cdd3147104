// Case 5, mirror corridor: two parallel lossless mirrors, the camera between
// them. A camera ray with lateral slopes (ty, tz) per unit of x meets the
// mirrors at lateral distances |t| (2n - 1), n = 1, 2, ..., and leaves the
// corridor through the side of its larger slope; the light closes the +y side.
// So a ray reads exactly 10 when ty > |tz| and 0 otherwise, unless it hits the
// mirrors more than max_depth times, i.e. max(|ty|, |tz|) <= 2 / (2 max_depth
// + 1): then the depth cap cuts it (counted) and it reads 0. Without the cap a
// ray on the axis would bounce forever. The test checks every pixel against
// that exact answer, the number of cut paths against its expectation, and that
// the work is bounded by paths x (max_depth + 1).
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

struct CorridorExpectation {
    std::vector<double> lit;    // per pixel: fraction of its area that reads 10
    std::vector<double> capped; // per pixel: fraction of its area the cap cuts
};

// Integrates the exact answer over each pixel's area on a fine grid (the
// camera's jitter is uniform in the pixel, in film coordinates).
CorridorExpectation expected_corridor(const Scene& scene, std::uint32_t max_depth) {
    const int w = scene.camera.width, h = scene.camera.height;
    const double half = std::tan(scene.camera.vertical_fov_degrees * M_PI / 360.0);
    const double aspect = static_cast<double>(w) / h;
    const double cap_slope = 2.0 / (2.0 * max_depth + 1.0);
    const int n = 64;
    CorridorExpectation e;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int lit = 0, capped = 0;
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    double sx = 2.0 * (x + (i + 0.5) / n) / w - 1.0;
                    double sy = 1.0 - 2.0 * (y + (j + 0.5) / n) / h;
                    // Looking along +x with up +z: the image's right is -y.
                    double ty = -sx * half * aspect, tz = sy * half;
                    bool cut = std::max(std::abs(ty), std::abs(tz)) <= cap_slope;
                    capped += cut;
                    lit += !cut && ty > std::abs(tz);
                }
            e.lit.push_back(static_cast<double>(lit) / (n * n));
            e.capped.push_back(static_cast<double>(capped) / (n * n));
        }
    return e;
}

} // namespace

TEST_CASE("mirror corridor: every pixel matches the exact answer and cut paths are counted",
          "[stability][corridor][statistical]") {
    Scene scene = stress_scene("mirror-corridor", 32);
    const std::uint32_t spp = 16, max_depth = 64;
    const double radiance = 10.0;
    IntegratorOptions options;
    options.max_depth = max_depth;
    test::Rendered r = test::render(scene, spp, 3, 0, options);
    CorridorExpectation e = expected_corridor(scene, max_depth);

    Image mean = r.film.mean();
    int outside = 0;
    double worst = 0.0, expected_capped = 0.0, capped_variance = 0.0;
    for (std::size_t p = 0; p < e.lit.size(); ++p) {
        double expected = radiance * e.lit[p];
        // Each sample reads 0 or 10: a binomial standard error (the film's own
        // is 0 when all of a pixel's few samples happen to agree).
        double sigma = radiance * std::sqrt(e.lit[p] * (1.0 - e.lit[p]) / spp);
        double d = std::abs(mean.rgb[p * 3] - expected);
        worst = std::max(worst, sigma > 0.0 ? d / sigma : (d > 1e-6 ? INFINITY : 0.0));
        if (d > kSigmas * sigma + 1e-6)
            ++outside;
        expected_capped += spp * e.capped[p];
        capped_variance += spp * e.capped[p] * (1.0 - e.capped[p]);
    }
    const double paths = static_cast<double>(spp) * static_cast<double>(e.lit.size());
    WARN("mirror corridor, max depth " << max_depth << ": " << outside << " pixels over 5 sigma "
                                       << "(worst " << worst << "); " << r.stats.capped_paths
                                       << " paths cut, expected " << expected_capped << " +- "
                                       << std::sqrt(capped_variance) << "; " << r.stats.bounce_rays
                                       << " bounce rays for " << paths << " paths");
    CHECK(outside == 0);
    CHECK(std::abs(static_cast<double>(r.stats.capped_paths) - expected_capped) <
          kSigmas * std::sqrt(capped_variance));
    CHECK(r.stats.capped_paths > 0);
    // Bounded work: no path traces more than max_depth + 1 rays.
    CHECK(static_cast<double>(r.stats.bounce_rays) <= paths * max_depth);
    CHECK(all_finite(r));
}

TEST_CASE("mirror corridor: with the default cap of 1024 bounces the render ends and counts "
          "its cut paths",
          "[stability][corridor][statistical]") {
    // A 2 degree view, so that a few dozen of the 16384 paths need more than
    // 1024 bounces and the rest up to a few hundred.
    Scene scene = stress_scene("mirror-corridor", 32);
    scene.camera.vertical_fov_degrees = 2.0;
    const std::uint32_t spp = 16;
    auto start = std::chrono::steady_clock::now();
    test::Rendered r = test::render(scene, spp, 3);
    double seconds = seconds_since(start);
    CorridorExpectation e = expected_corridor(scene, IntegratorOptions{}.max_depth);
    double expected_capped = 0.0, variance = 0.0, bias = 0.0;
    for (std::size_t p = 0; p < e.capped.size(); ++p) {
        expected_capped += spp * e.capped[p];
        variance += spp * e.capped[p] * (1.0 - e.capped[p]);
    }
    // The cap's bias: a cut path near the axis would have left the corridor
    // eventually, a quarter of them (ty > |tz|) into the light.
    bias = 10.0 * 0.25 * expected_capped / (spp * static_cast<double>(e.capped.size()));
    WARN("mirror corridor, max depth 1024: "
         << r.stats.capped_paths << " paths cut (expected " << expected_capped << " +- "
         << std::sqrt(variance) << "), bias of the image mean about -" << bias << ", "
         << r.stats.bounce_rays << " bounce rays, " << seconds << " s");
    CHECK(std::abs(static_cast<double>(r.stats.capped_paths) - expected_capped) <
          kSigmas * std::sqrt(variance));
    CHECK(r.stats.capped_paths > 0);
    CHECK(static_cast<double>(r.stats.bounce_rays) <=
          spp * static_cast<double>(e.capped.size()) * 1024.0);
    CHECK(all_finite(r));
}
