// Choosing an emissive triangle by power (render/light_pick.hpp,
// WP_HAS_POWER_LIGHT_PICK): the same image as the pick by area, within
// noise, with far less noise where the bright lamp lights the floor; the
// multiple importance sampling weights of the light sample and the BSDF
// sample still sum to one; and the switch is on only where the triangles'
// luminances differ. Independent samples, so that the films' sample
// variances are honest error bars; tolerances are 5 combined standard errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "render/device_scene.hpp"
#include "render/light_pick.hpp"
#include "scene/load.hpp"
#include "scene/luminance.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

constexpr double kSigmas = 5.0;

// A dim 2 x 2 panel and a bright 0.2 x 0.2 lamp with 10 times its power
// over a floor, a rough gold plate behind (scenes/lights/unequal-lamps.json).
Scene unequal_lamps(int size) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/lights/unequal-lamps.json");
    scene.camera.width = size;
    scene.camera.height = size;
    return scene;
}

IntegratorOptions with_pick(LightPick pick) {
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    options.light_pick = pick;
    return options;
}

// Image mean and 8x8 block means of two renders of the same image, channel
// by channel, within 5 combined standard errors.
void check_agree(const test::Rendered& a, const test::Rendered& b, const char* what) {
    for (int ch = 0; ch < 3; ++ch) {
        const test::MeanWithError ma = test::image_mean(a.film, ch),
                                  mb = test::image_mean(b.film, ch);
        INFO(what << ", channel " << ch << ": " << ma.mean << " +- " << ma.standard_error
                  << " against " << mb.mean << " +- " << mb.standard_error << ": "
                  << test::sigmas_apart(ma, mb) << " sigma");
        CHECK(test::sigmas_apart(ma, mb) < kSigmas);
        CHECK(ma.standard_error < 0.01 * ma.mean); // the test has power
    }
    const test::BlockComparison blocks = test::compare_blocks(a.film, b.film, 8, kSigmas);
    INFO(what << ": largest block deviation " << blocks.worst_sigmas << " combined sigma, "
              << blocks.worst_where);
    CHECK(blocks.outside == 0);
}

} // namespace

TEST_CASE("light pick: by power only where the triangles' luminances differ", "[light-pick]") {
    const Scene lamps = unequal_lamps(8);
    CHECK(triangle_radiances_differ(lamps));
    CHECK(analyse_features(lamps).power_light_pick);
    CHECK(integrator_features(lamps, with_pick(LightPick::Area)).power_light_pick == false);
    // The hexroom's one light keeps the area pick's code (and bits: the golden images).
    const Scene hexroom = test::hexroom(8, 8);
    CHECK_FALSE(triangle_radiances_differ(hexroom));
    CHECK_FALSE(analyse_features(hexroom).power_light_pick);

    // The table: the lamp (the last two triangles) takes its share of the
    // power, area x luminance; emission.w holds total power / luminance.
    const DeviceScene power = flatten_scene(lamps, false, LightPick::Power);
    const DeviceScene area = flatten_scene(lamps, false, LightPick::Area);
    REQUIRE(power.lights.size() == 4);
    const double panel = 4.0 * luminance(glm::dvec3(1.0));
    const double lamp = 0.04 * luminance(glm::dvec3(1200, 1000, 800));
    CHECK(power.lights[1].cdf == Approx(panel / (panel + lamp)).epsilon(1e-5));
    CHECK(area.lights[1].cdf == Approx(4.0 / 4.04).epsilon(1e-5));
    const double lamp_spread = (panel + lamp) / luminance(glm::dvec3(1200, 1000, 800));
    CHECK(power.materials[lamps.triangles.back().material].emission.s[3] ==
          Approx(lamp_spread * (power.light_area / 4.04)).epsilon(1e-5));
    // By area every light's emission.w is the total area, bit for bit.
    for (const WpLight& light : area.lights)
        CHECK(area.materials[lamps.triangles[light.triangle].material].emission.s[3] ==
              area.light_area);
}

TEST_CASE("light pick: power and area agree within noise, power with less noise at the bright "
          "lamp's pixels",
          "[light-pick][statistical]") {
    const Scene scene = unequal_lamps(32);
    const test::Rendered power = test::render(scene, 256, 3, 0, with_pick(LightPick::Power));
    const test::Rendered area = test::render(scene, 256, 4, 0, with_pick(LightPick::Area));
    CHECK(power.stats.nonfinite_samples == 0);
    check_agree(power, area, "power against area");

    // The pixels the bright lamp lights: the floor under it, where the
    // image is brightest (over a quarter of its largest pixel mean).
    const Image mean = power.film.mean();
    const Image power_variance = power.film.variance_of_mean();
    const Image area_variance = area.film.variance_of_mean();
    double brightest = 0.0;
    for (std::size_t p = 0; p < mean.rgb.size(); p += 3)
        brightest = std::max(brightest, double(mean.rgb[p + 1]));
    double sum_power = 0.0, sum_area = 0.0;
    int pixels = 0;
    for (std::size_t p = 0; p < mean.rgb.size(); p += 3)
        if (mean.rgb[p + 1] > 0.25 * brightest) {
            sum_power += power_variance.rgb[p + 1];
            sum_area += area_variance.rgb[p + 1];
            ++pixels;
        }
    const double ratio = sum_area / sum_power;
    std::printf("light pick: at the bright lamp's %d pixels the area pick's variance is %.1fx "
                "the power pick's (green, 256 spp each)\n",
                pixels, ratio);
    CHECK(pixels >= 8);
    CHECK(ratio > 10.0);
}

TEST_CASE("light pick: the power pick's multiple importance sampling weights sum to one",
          "[light-pick][statistical]") {
    // With --mis light a BSDF sample's hit on a lamp counts 0 and the light
    // sample counts alone; with the power heuristic both count, weighed by
    // the power pick's density on both sides. Only if those weights sum to
    // one on every path do the two images agree (the gold plate reflects
    // both lamps, and every diffuse vertex weighs too).
    const Scene scene = unequal_lamps(32);
    IntegratorOptions mis = with_pick(LightPick::Power);
    IntegratorOptions light_only = mis;
    light_only.mis = MisStrategy::LightOnly;
    const test::Rendered weighed = test::render(scene, 256, 5, 0, mis);
    const test::Rendered alone = test::render(scene, 256, 6, 0, light_only);
    check_agree(weighed, alone, "power heuristic against light sampling alone");
}
