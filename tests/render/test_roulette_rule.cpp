// The two roulette rules (--roulette, kernels/estimator.h) are both unbiased:
// on a small showcase (smooth and rough glass, metals, plastics, textures, an
// environment map and an area light) their images agree in the whole-image
// mean and in 4x4-pixel block means within 5 combined standard errors, with
// roulette from the first bounce and from the fifth. The default, 'auto',
// takes Mitsuba's rule exactly where a scene refracts.
#include <catch2/catch.hpp>

#include <string>

#include "render/integrator_options.hpp"
#include "render/prepared_scene.hpp"
#include "render/wavefront.hpp"
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
        throughput_rule.roulette_rule = RouletteRule::Throughput;
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

TEST_CASE("roulette rule: 'auto' is Mitsuba's where a dielectric or roughdielectric refracts, "
          "throughput elsewhere, and a rule given stays",
          "[render][roulette]") {
    const std::string scenes = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/";
    const Scene showcase = load_scene(scenes + "materials/showcase.json");
    const Scene hexroom = load_scene(scenes + "hexroom.json");
    const IntegratorOptions automatic;
    REQUIRE(automatic.roulette_rule == RouletteRule::Auto);

    CHECK(with_scene_settings(automatic, showcase).roulette_rule == RouletteRule::Mitsuba);
    CHECK(with_scene_settings(automatic, hexroom).roulette_rule == RouletteRule::Throughput);

    // One refracting material is enough, smooth or rough; a thin pane (no
    // eta^2 along the path) and the other kinds are not.
    for (const auto& [kind, expected] :
         {std::pair{MaterialKind::Dielectric, RouletteRule::Mitsuba},
          std::pair{MaterialKind::RoughDielectric, RouletteRule::Mitsuba},
          std::pair{MaterialKind::ThinDielectric, RouletteRule::Throughput},
          std::pair{MaterialKind::RoughConductor, RouletteRule::Throughput},
          std::pair{MaterialKind::Plastic, RouletteRule::Throughput}}) {
        Scene scene = hexroom;
        scene.materials.back().kind = kind;
        INFO("material kind " << material_kind_name(kind));
        CHECK(with_scene_settings(automatic, scene).roulette_rule == expected);
    }

    for (const RouletteRule given : {RouletteRule::Throughput, RouletteRule::Mitsuba}) {
        IntegratorOptions options;
        options.roulette_rule = given;
        CHECK(with_scene_settings(options, showcase).roulette_rule == given);
        CHECK(with_scene_settings(options, hexroom).roulette_rule == given);
    }

    // What the kernels are built with: the prepared scene's resolved rule.
    const PreparedScene prepared = prepare_scene(showcase, automatic);
    CHECK(kernel_build_options(prepared.features, prepared.options).find("-D WP_ROULETTE_RULE=1") !=
          std::string::npos);
    const PreparedScene plain = prepare_scene(hexroom, automatic);
    CHECK(kernel_build_options(plain.features, plain.options).find("WP_ROULETTE_RULE") ==
          std::string::npos);
}
