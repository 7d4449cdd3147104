// The error breakdown's arithmetic (report/error_breakdown.hpp): the shares
// of the variance sum to the whole's, and the near-light region and the means
// over it.
#include <catch2/catch.hpp>

#include <vector>

#include "render/integrator_options.hpp"
#include "report/error_breakdown.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

IntegratorOptions with_types(std::uint32_t types) {
    IntegratorOptions options;
    options.path_types = types;
    return options;
}

} // namespace

TEST_CASE("path types: the shares of the variance sum to the whole's") {
    // Cov(X_k, X) summed over the parts is Var X; with the three films of one
    // seed that holds for the sample (co)variances too, to rounding.
    const Scene scene = test::hexroom(16, 16);
    const Image whole = test::render(scene, 32, 9, 0, {}).film.variance_of_mean();
    std::vector<double> sum(whole.rgb.size(), 0.0);
    for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT; ++type) {
        const std::uint32_t alone = 1u << type;
        const Image part = test::render(scene, 32, 9, 0, with_types(alone)).film.variance_of_mean();
        const Image rest = test::render(scene, 32, 9, 0, with_types(kAllPathTypes & ~alone))
                               .film.variance_of_mean();
        const Image share = variance_share(whole, part, rest);
        for (std::size_t i = 0; i < sum.size(); ++i)
            sum[i] += share.rgb[i];
    }
    double total = 0.0, shares = 0.0;
    for (std::size_t i = 0; i < sum.size(); ++i) {
        total += whole.rgb[i];
        shares += sum[i];
    }
    CHECK(total > 0.0);
    CHECK(shares == Approx(total).epsilon(1e-3));
}

TEST_CASE("error breakdown: the near-light region and means over it") {
    Image image(5, 4);
    image.rgb[(1 * 5 + 1) * 3 + 2] = 50.0f; // pixel (1, 1), blue channel
    const std::vector<bool> region = bright_region(image, 10.0, 1);
    int inside = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) {
            const bool expected = x <= 2 && y <= 2;
            CHECK(region[static_cast<std::size_t>(y) * 5 + x] == expected);
            inside += expected;
        }
    CHECK(region_fraction(region) == Approx(inside / 20.0));
    const RegionMeans m = region_means(image, region);
    CHECK(m.inside == Approx(50.0 / 60.0));
    CHECK(m.outside == 0.0);
    CHECK(m.total == Approx(50.0 / 60.0));
}
