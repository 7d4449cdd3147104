// Profiling: the counts in the profile are exact and consistent (the files
// written from it are tested in tests/report/test_profile_report.cpp).
#include <catch2/catch.hpp>

#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

// The tests that .ci/oclgrind-check runs on the simulator cap the path
// length, so that a path trapped between mirrors cannot keep its wave
// launching for a thousand iterations (the counts hold at any depth).
constexpr std::uint32_t kOclgrindDepth = 8;

StageTotals totals(const Profiler& p, Stage s) {
    return p.totals()[static_cast<int>(s)];
}

} // namespace

TEST_CASE("profile: stage item counts are exact and consistent") {
    // Small enough for the Oclgrind step (.ci/oclgrind-check runs it on the
    // simulator), large enough that the 37-slot pool refills many times.
    const int width = 10, height = 6;
    const std::uint32_t spp = 4;
    const std::uint64_t samples = std::uint64_t{width} * height * spp;
    for (bool regeneration : {true, false}) {
        for (std::uint32_t pool : {0u, 37u}) {
            INFO("regeneration " << regeneration << ", pool " << pool);
            test::ProfiledRender r = test::profiled_render(test::hexroom(width, height), spp,
                                                           regeneration, pool, kOclgrindDepth);
            std::uint64_t queued = 0;
            for (std::uint32_t length : r.stats.queue_lengths)
                queued += length;
            CHECK(r.stats.camera_rays == samples);
            CHECK(totals(r.profiler, Stage::Generate).items == samples);
            CHECK(totals(r.profiler, Stage::Accumulate).items == samples);
            // Without regeneration a wave's last rays go to the tail kernel
            // (kernels/tail.cl), whose items are the rays it traced.
            const std::uint64_t tail = totals(r.profiler, Stage::Tail).items;
            if (regeneration)
                CHECK(tail == 0);
            CHECK(totals(r.profiler, Stage::Intersect).items + tail == queued);
            CHECK(totals(r.profiler, Stage::Shade).items + tail == queued);
            CHECK(queued == r.stats.camera_rays + r.stats.bounce_rays);
            if (!regeneration && pool == 0) {
                // One wave per sample: bounce 0 traces every camera ray.
                std::uint64_t per_bounce = 0;
                for (std::uint64_t rays : r.stats.rays_per_bounce)
                    per_bounce += rays;
                CHECK(per_bounce == queued);
                REQUIRE_FALSE(r.stats.rays_per_bounce.empty());
                CHECK(r.stats.rays_per_bounce[0] == samples);
            }
            // The tail kernel traces its shadow rays itself.
            if (tail == 0)
                CHECK(totals(r.profiler, Stage::Shadow).items == r.stats.shadow_rays);
            else
                CHECK(totals(r.profiler, Stage::Shadow).items < r.stats.shadow_rays);
            CHECK(r.film.min_samples() == spp);
            CHECK(r.film.total_samples() == samples);
            // Stage times are real and fit inside the wall time.
            CHECK(r.profiler.device_busy_seconds() > 0.0);
            CHECK(r.profiler.device_busy_seconds() <= r.stats.render_seconds);
        }
    }
}

TEST_CASE("profile: a render call ends with its last sample, not with a launch over an empty "
          "queue") {
    // Once the last sample has finished, a refill finds no slot with work; an
    // iteration after it would launch intersect over the whole pool (without
    // regeneration) for nothing, and where intersect vectorises each of those
    // items traces a ray (kernels/traverse.h). Every iteration must trace.
    const int width = 10, height = 6;
    for (bool regeneration : {true, false}) {
        for (std::uint32_t pool : {0u, 37u}) {
            INFO("regeneration " << regeneration << ", pool " << pool);
            test::ProfiledRender r = test::profiled_render(test::hexroom(width, height), 3,
                                                           regeneration, pool, kOclgrindDepth);
            REQUIRE_FALSE(r.stats.queue_lengths.empty());
            for (std::uint32_t length : r.stats.queue_lengths)
                CHECK(length > 0);
            std::uint64_t launches = 0;
            for (const LaunchRecord& record : r.profiler.records())
                if (record.stage == Stage::Intersect || record.stage == Stage::Tail) {
                    ++launches;
                    CHECK(record.items > 0);
                }
            CHECK(launches == r.stats.iterations);
            CHECK(r.film.total_samples() == std::uint64_t{width} * height * 3);
        }
    }
}

TEST_CASE("profile: every diffuse hit below a light sends exactly one shadow ray") {
    // A floor seen through a narrow view, lit from above: every camera ray
    // hits the floor, every floor point sees the light's front, and bounce
    // rays can only hit the light or escape. So shadow rays = camera rays.
    Scene scene;
    auto floor = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    auto light = test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(1.0));
    test::add_quad(scene, {-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}, floor);
    test::add_quad(scene, {-1, -1, 2}, {-1, 1, 2}, {1, 1, 2}, {1, -1, 2}, light);
    scene.camera = test::make_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 10.0, 8, 8);
    test::ProfiledRender r = test::profiled_render(scene, 16, true);
    CHECK(r.stats.camera_rays == 8u * 8u * 16u);
    CHECK(totals(r.profiler, Stage::Shadow).items == r.stats.camera_rays);
    CHECK(r.stats.shadow_rays == r.stats.camera_rays);
}

TEST_CASE("profile: regeneration changes the schedule, not the image") {
    Scene scene = test::hexroom(10, 8);
    test::ProfiledRender wave = test::profiled_render(scene, 4, false, 0, kOclgrindDepth);
    test::ProfiledRender regen = test::profiled_render(scene, 4, true, 0, kOclgrindDepth);
    // Same samples, summed in a different order of flushes.
    Image a = wave.film.mean(), b = regen.film.mean();
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        REQUIRE(a.rgb[i] == Approx(b.rgb[i]).epsilon(1e-5).margin(1e-6));
    // Refilling keeps queues full: fewer, fuller launches.
    CHECK(regen.stats.iterations < wave.stats.iterations);
    // The same rays, some of them traced by the tail kernel without regeneration.
    CHECK(totals(regen.profiler, Stage::Tail).items == 0);
    CHECK(totals(regen.profiler, Stage::Intersect).items ==
          totals(wave.profiler, Stage::Intersect).items + totals(wave.profiler, Stage::Tail).items);
}

TEST_CASE("render: requests whose task counts would wrap 32 bits are split") {
    // 4096 x 4096 on 16 slots: each slot owns 2^20 pixels, so 4096 samples
    // would be 2^32 tasks; one call may hold at most 4095.
    CHECK(WavefrontIntegrator::max_samples_per_call(4096ull * 4096, 16) == 4095u);
    CHECK(WavefrontIntegrator::max_samples_per_call(800ull * 800, 800ull * 800) == 0xffffffffu);
    // Splitting is invisible: a small pool renders the same image.
    Scene scene = test::hexroom(7, 5);
    test::ProfiledRender full = test::profiled_render(scene, 3, false, 0, kOclgrindDepth);
    test::ProfiledRender tiny = test::profiled_render(scene, 3, false, 5, kOclgrindDepth);
    Image a = full.film.mean(), b = tiny.film.mean();
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        REQUIRE(a.rgb[i] == Approx(b.rgb[i]).epsilon(1e-5).margin(1e-6));
}
