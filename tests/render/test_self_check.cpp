// The kernels' self-check (render/self_check.hpp): the specialised and
// general kernels agree on PoCL, the verdict is remembered in the program
// cache, and a fault injected into the specialised build is caught and
// answered with the general kernels.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <optional>
#include <string>

#include "render/self_check.hpp"
#include "support/env_guard.hpp"
#include "support/render_helpers.hpp"
#include "support/temp_dir.hpp"

using namespace wp;

namespace {

using test::EnvGuard;

// The built-in scene of `wavepath devices --check` (every feature, 14
// triangles and 2 spheres: quick to compile), at 8x8.
Scene small_scene() {
    Scene scene = self_check_scene();
    scene.camera.width = scene.camera.height = 8;
    return scene;
}

} // namespace

TEST_CASE("self-check: the variants agree on PoCL, a fault in one is caught, verdicts are kept") {
    test::TempDir cache; // a fresh cache: nothing is remembered yet
    EnvGuard enabled("WAVEPATH_SELF_CHECK", nullptr);
    IntegratorOptions options;
    options.self_check = true;
    options.program_cache = CachePolicy::in(cache.path());
    const Scene scene = small_scene();

    {
        EnvGuard fault("WAVEPATH_SELF_CHECK_FAULT", nullptr);
        WavefrontIntegrator first(test::device(), scene, options);
        REQUIRE(first.self_check());
        CHECK(first.self_check()->passed);
        CHECK(first.self_check()->detail == "bit for bit");
        CHECK_FALSE(first.self_check()->from_cache);
        CHECK(first.program().options.find("WP_TRIANGLE_COUNT=14") != std::string::npos);

        WavefrontIntegrator again(test::device(), scene, options);
        REQUIRE(again.self_check());
        CHECK(again.self_check()->passed);
        CHECK(again.self_check()->from_cache);
    }
    {
        // The specialised build draws other random numbers: caught, and the
        // integrator builds the general kernels instead.
        EnvGuard fault("WAVEPATH_SELF_CHECK_FAULT", "1");
        WavefrontIntegrator faulty(test::device(), scene, options);
        REQUIRE(faulty.self_check());
        CHECK_FALSE(faulty.self_check()->passed);
        INFO(faulty.self_check()->detail);
        CHECK(faulty.self_check()->detail.find("of values differ") != std::string::npos);
        const std::string& built = faulty.program().options;
        CHECK(built.find("WP_TRIANGLE_COUNT") == std::string::npos);
        CHECK(built.find("WP_SAMPLER=1") != std::string::npos); // the sampler asked for

        WavefrontIntegrator remembered(test::device(), scene, options);
        REQUIRE(remembered.self_check());
        CHECK_FALSE(remembered.self_check()->passed);
        CHECK(remembered.self_check()->from_cache);
    }
    {
        // Off: no check, the specialised kernels as asked.
        EnvGuard off("WAVEPATH_SELF_CHECK", "0");
        WavefrontIntegrator unchecked(test::device(), scene, options);
        CHECK_FALSE(unchecked.self_check());
    }
}
