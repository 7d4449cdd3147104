// The two roulette rules (--roulette, kernels/estimator.h) are both unbiased:
// on a small showcase (smooth and rough glass, metals, plastics, textures, an
// environment map and an area light) their images agree in the whole-image
// mean and in 4x4-pixel block means within 5 combined standard errors, with
// roulette from the first bounce and from the fifth. The default, 'auto',
// takes Mitsuba's rule exactly where a scene refracts. Where roulette starts
// by default: from bounce 1, and from kEnvironmentRouletteDepth in a scene lit
// by an environment, whose image is the same (5 sigma again).
#include <catch2/catch.hpp>

#include <string>

#include "render/integrator_options.hpp"
#include "render/prepared_scene.hpp"
#include "render/wavefront.hpp"
#include "scene/load.hpp"
#include "support/render_helpers.hpp"

using namespace wp;
using namespace wp::test;

namespace {

// a and b, renders of one scene by two unbiased estimators, agree: the image
// means and every 4x4 block's mean within 5 combined standard errors.
void check_same_image(const Rendered& a, const Rendered& b, const std::string& what) {
    CHECK(a.stats.nonfinite_samples == 0);
    CHECK(b.stats.nonfinite_samples == 0);
    for (int c = 0; c < 3; ++c) {
        const MeanWithError ma = image_mean(a.film, c), mb = image_mean(b.film, c);
        INFO(what << ", channel " << c << ": " << ma.mean << " +- " << ma.standard_error
                  << " against " << mb.mean << " +- " << mb.standard_error);
        CHECK(sigmas_apart(ma, mb) < 5.0);
    }
    const BlockComparison blocks = compare_blocks(a.film, b.film, 4);
    INFO(what << ": " << blocks.outside << " of " << blocks.blocks
              << " block means more than 5 sigma apart, the worst " << blocks.worst_where);
    CHECK(blocks.outside == 0);
}

Scene small_showcase() {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/materials/showcase.json");
    scene.camera.width = 24;
    scene.camera.height = 16;
    return scene;
}

} // namespace

TEST_CASE("roulette rule: Mitsuba's rule and the default estimate the same image",
          "[render][roulette][statistical]") {
    const Scene scene = small_showcase();
    for (const std::uint32_t depth : {1u, 5u}) {
        IntegratorOptions throughput_rule, mitsuba_rule;
        throughput_rule.roulette_depth = mitsuba_rule.roulette_depth = depth;
        throughput_rule.roulette_depth_given = mitsuba_rule.roulette_depth_given = true;
        throughput_rule.roulette_rule = RouletteRule::Throughput;
        mitsuba_rule.roulette_rule = RouletteRule::Mitsuba;
        check_same_image(
            render(scene, 256, 3, 0, throughput_rule), render(scene, 256, 4, 0, mitsuba_rule),
            "roulette from " + std::to_string(depth) + ", throughput rule against Mitsuba's");
    }
}

TEST_CASE("roulette rule: Cycles' rule and the relative rule estimate the throughput rule's image",
          "[render][roulette][statistical]") {
    // The Cornell box (coloured walls: the relative rule's first bounce
    // keeps 0.45 to 0.73 of the throughput) and the hexroom (mirrors), small.
    const std::string scenes = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/";
    for (const std::string name : {"cornell-box.json", "hexroom.json"}) {
        Scene scene = load_scene(scenes + name);
        scene.camera.width = 16;
        scene.camera.height = 16;
        IntegratorOptions throughput_rule;
        throughput_rule.roulette_rule = RouletteRule::Throughput;
        for (const RouletteRule rule : {RouletteRule::Sqrt, RouletteRule::Relative}) {
            IntegratorOptions other;
            other.roulette_rule = rule;
            check_same_image(render(scene, 256, 7, 0, throughput_rule),
                             render(scene, 256, 8, 0, other),
                             name + ": the throughput rule against " + to_string(rule));
        }
    }
}

TEST_CASE("roulette depth: the environment's later start estimates the image of roulette from "
          "bounce 1",
          "[render][roulette][statistical]") {
    const Scene scene = small_showcase();
    IntegratorOptions first_bounce;
    first_bounce.roulette_depth = 1;
    first_bounce.roulette_depth_given = true;
    REQUIRE(with_scene_settings(IntegratorOptions{}, scene).roulette_depth ==
            kEnvironmentRouletteDepth);
    check_same_image(
        render(scene, 256, 5, 0, IntegratorOptions{}), render(scene, 256, 6, 0, first_bounce),
        "roulette from " + std::to_string(kEnvironmentRouletteDepth) + " against from 1");
}

TEST_CASE("roulette depth: 1, and kEnvironmentRouletteDepth in a scene lit by an envmap or a "
          "constant emitter, unless given or a Mitsuba file's rr_depth",
          "[render][roulette]") {
    const std::string scenes = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/";
    const Scene showcase = load_scene(scenes + "materials/showcase.json");
    const Scene hexroom = load_scene(scenes + "hexroom.json");
    const IntegratorOptions automatic;
    REQUIRE(automatic.roulette_depth == 1u);
    REQUIRE(!automatic.roulette_depth_given);
    CHECK(with_scene_settings(automatic, showcase).roulette_depth == kEnvironmentRouletteDepth);
    CHECK(with_scene_settings(automatic, hexroom).roulette_depth == 1u);

    // A constant emitter lights from everywhere too; a point light does not.
    for (const auto& [kind, expected] :
         {std::pair{EmitterKind::Constant, kEnvironmentRouletteDepth},
          std::pair{EmitterKind::Point, 1u}}) {
        Scene scene = hexroom;
        Emitter emitter;
        emitter.kind = kind;
        scene.emitters.push_back(emitter);
        INFO("a hexroom with an emitter of kind " << static_cast<int>(kind));
        CHECK(with_scene_settings(automatic, scene).roulette_depth == expected);
    }

    IntegratorOptions given;
    given.roulette_depth = 3;
    given.roulette_depth_given = true;
    CHECK(with_scene_settings(given, showcase).roulette_depth == 3u);
    given.roulette_depth = 1;
    CHECK(with_scene_settings(given, showcase).roulette_depth == 1u);

    Scene file = showcase; // a Mitsuba file's rr_depth counts as given
    file.rr_depth = 5;
    CHECK(with_scene_settings(automatic, file).roulette_depth == 5u);

    // What the kernels are built with: the prepared scene's resolved depth.
    const PreparedScene prepared = prepare_scene(showcase, automatic);
    CHECK(kernel_build_options(prepared.features, prepared.options)
              .find("-D WP_ROULETTE_DEPTH=" + std::to_string(kEnvironmentRouletteDepth)) !=
          std::string::npos);
}

TEST_CASE("roulette rule: 'auto' is Mitsuba's where a dielectric or roughdielectric refracts, "
          "relative in a room without mirrors or an environment, throughput elsewhere, and a "
          "rule given stays",
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

    // The Cornell bunny: diffuse, lit by its area light, no mirror. A mirror,
    // an environment or glass each take the relative rule away.
    const Scene bunny = load_scene(scenes + "cornell-bunny.json");
    CHECK(with_scene_settings(automatic, bunny).roulette_rule == RouletteRule::Relative);
    for (const auto& [kind, expected] :
         {std::pair{MaterialKind::Mirror, RouletteRule::Throughput},
          std::pair{MaterialKind::Dielectric, RouletteRule::Mitsuba},
          std::pair{MaterialKind::RoughConductor, RouletteRule::Relative},
          std::pair{MaterialKind::Diffuse, RouletteRule::Relative}}) {
        Scene scene = bunny;
        scene.materials.back().kind = kind;
        INFO("bunny, material kind " << material_kind_name(kind));
        CHECK(with_scene_settings(automatic, scene).roulette_rule == expected);
    }
    Scene bunny_outdoors = bunny;
    Emitter sky;
    sky.kind = EmitterKind::Constant;
    bunny_outdoors.emitters.push_back(sky);
    CHECK(with_scene_settings(automatic, bunny_outdoors).roulette_rule == RouletteRule::Throughput);

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
