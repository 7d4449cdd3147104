// The split of the estimate by path type (kernels/path_type.h, `--path-types`):
// the parts of one seed sum to the full image, each is non-negative, a part
// the scene cannot produce is black, and in the furnace box each part has its
// closed form.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "render/integrator_options.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

constexpr double kSigmas = 5.0;

IntegratorOptions with_types(std::uint32_t types, bool nee = true) {
    IntegratorOptions options;
    options.path_types = types;
    options.next_event_estimation = nee;
    return options;
}

Image render_mean(const Scene& scene, std::uint32_t spp, std::uint32_t types, bool nee = true) {
    return test::render(scene, spp, 7, 0, with_types(types, nee)).film.mean();
}

// A sample's radiance is a float sum of a few contributions and the device
// film a float sum of about ten samples, both of non-negative terms, so the
// parts' sum and the full image differ by rounding of at most a few dozen
// float ulps of the pixel's value (2^-24 each); the bound leaves room for it
// and for values near zero.
void check_parts_sum_to_whole(const Scene& scene, std::uint32_t spp, bool nee) {
    const Image whole = render_mean(scene, spp, kAllPathTypes, nee);
    std::vector<double> sum(whole.rgb.size(), 0.0);
    double largest = 0.0;
    for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT; ++type) {
        const Image part = render_mean(scene, spp, 1u << type, nee);
        for (std::size_t i = 0; i < part.rgb.size(); ++i)
            sum[i] += part.rgb[i];
        CHECK(*std::min_element(part.rgb.begin(), part.rgb.end()) >= 0.0f);
    }
    int outside = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const double tolerance = 64.0 * std::ldexp(1.0, -24) * whole.rgb[i] + 1e-30;
        const double error = std::abs(sum[i] - whole.rgb[i]);
        worst = std::max(worst, whole.rgb[i] > 0.0f ? error / whole.rgb[i] : error);
        largest = std::max(largest, static_cast<double>(whole.rgb[i]));
        if (error > tolerance)
            ++outside;
    }
    INFO("worst relative difference " << worst << " (float epsilon 1.19e-7)");
    CHECK(outside == 0);
    CHECK(largest > 0.0); // the image is not black
}

Scene furnace_box(glm::dvec3 emission, double albedo) {
    Scene scene;
    auto wall = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(albedo), emission);
    test::add_box_inward(scene, glm::dvec3(-1.0), glm::dvec3(1.0), wall);
    scene.camera = test::make_camera({0.2, -0.1, 0.3}, {1, 0.3, 0.1}, {0, 0, 1}, 100.0, 16, 16);
    return scene;
}

} // namespace

TEST_CASE("path types: the parts of one seed sum to the full image, float rounding aside") {
    const Scene scene = test::hexroom(32, 32);
    SECTION("with next-event estimation") {
        check_parts_sum_to_whole(scene, 16, true);
    }
    SECTION("without") {
        check_parts_sum_to_whole(scene, 16, false);
    }
}

TEST_CASE("path types: the hexroom has light of every type") {
    const Scene scene = test::hexroom(32, 32);
    for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT; ++type) {
        INFO("path type " << path_type_name(type));
        const Image part = render_mean(scene, 16, 1u << type);
        CHECK(*std::max_element(part.rgb.begin(), part.rgb.end()) > 0.0f);
    }
}

TEST_CASE("path types: in the furnace box each part has its closed form, the mirror ones are 0",
          "[statistical]") {
    // Walls of albedo rho emitting Le, no mirror: Le = Le + rho Le + rho^2 Le
    // + ..., the camera part Le (every ray hits a wall), the direct part rho Le
    // (next-event estimation sees emitting walls all around: irradiance pi Le)
    // and the indirect part the rest, rho^2 Le / (1 - rho).
    const glm::dvec3 emission(1.0, 0.5, 0.25);
    const double rho = 0.5;
    const Scene scene = furnace_box(emission, rho);
    const double factor[WP_PATH_TYPE_COUNT] = {1.0, rho, rho * rho / (1.0 - rho), 0.0, 0.0};
    const bool nee = GENERATE(true, false);
    for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT; ++type) {
        INFO("path type " << path_type_name(type) << (nee ? ", with" : ", without")
                          << " next-event estimation");
        const test::Rendered r = test::render(scene, 256, 3, 0, with_types(1u << type, nee));
        for (int c = 0; c < 3; ++c) {
            const test::MeanWithError m = test::image_mean(r.film, c);
            const double expected = factor[type] * emission[c];
            INFO("channel " << c << ": " << m.mean << " +- " << m.standard_error << ", expected "
                            << expected);
            if (expected == 0.0) {
                CHECK(m.mean == 0.0); // no mirror, no light of this type at all
            } else if (type == WP_PATH_TYPE_CAMERA) {
                CHECK(m.standard_error < 1e-6 * expected); // every sample reads Le exactly
                CHECK(m.mean == Approx(expected).epsilon(1e-6));
            } else {
                // Plus float rounding: where roulette does not end the
                // first bounce (the relative rule) every direct sample
                // without next-event estimation reads rho Le exactly.
                CHECK(std::abs(m.mean - expected) <= kSigmas * m.standard_error + 1e-6 * expected);
                CHECK(m.standard_error < 0.02 * expected); // the test has power
            }
        }
    }
}

TEST_CASE("path types: names and lists") {
    CHECK(parse_path_types("all") == kAllPathTypes);
    CHECK(parse_path_types("direct") == 1u << WP_PATH_TYPE_DIRECT);
    CHECK(parse_path_types("caustic,camera") ==
          ((1u << WP_PATH_TYPE_CAUSTIC) | (1u << WP_PATH_TYPE_CAMERA)));
    CHECK(describe_path_types(parse_path_types("mirror,indirect")) == "indirect,mirror");
    CHECK(describe_path_types(kAllPathTypes) == "all");
    CHECK_THROWS_AS(parse_path_types("direkt"), std::invalid_argument);
    CHECK_THROWS_AS(parse_path_types("direct,"), std::invalid_argument);
    CHECK_THROWS_AS(parse_path_types(""), std::invalid_argument);
    IntegratorOptions options;
    CHECK(describe_estimator(options) == "cosine+nee+area");
    options.path_types = parse_path_types("caustic");
    CHECK(describe_estimator(options) == "cosine+nee+area+paths=caustic");
}
