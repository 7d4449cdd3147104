// Profiling: the counts in the profile are exact and consistent, and the
// JSON and trace files hold what they claim.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "render/profile_report.hpp"
#include "scene/load.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

DeviceContext& profiling_device() {
    static DeviceContext context(test::device().info, true);
    return context;
}

struct ProfiledRender {
    Profiler profiler;
    RenderStats stats;
    Film film;
};

ProfiledRender profiled_render(const Scene& scene, std::uint32_t spp, bool regeneration,
                               std::uint32_t pool = 0) {
    IntegratorOptions options;
    options.seed = 5;
    options.regeneration = regeneration;
    options.pool_size = pool;
    WavefrontIntegrator integrator(profiling_device(), scene, options);
    ProfiledRender out{{}, {}, Film(scene.camera.width, scene.camera.height)};
    integrator.set_profiler(&out.profiler);
    integrator.render(0, spp, out.film);
    out.stats = integrator.stats();
    return out;
}

Scene small_hexroom(int width, int height) {
    Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/scenes/hexroom.json");
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

StageTotals totals(const Profiler& p, Stage s) {
    return p.totals()[static_cast<int>(s)];
}

} // namespace

TEST_CASE("profile: stage item counts are exact and consistent") {
    const int width = 20, height = 12;
    const std::uint32_t spp = 6;
    const std::uint64_t samples = std::uint64_t{width} * height * spp;
    for (bool regeneration : {true, false}) {
        for (std::uint32_t pool : {0u, 37u}) {
            INFO("regeneration " << regeneration << ", pool " << pool);
            ProfiledRender r =
                profiled_render(small_hexroom(width, height), spp, regeneration, pool);
            std::uint64_t queued = 0;
            for (std::uint32_t length : r.stats.queue_lengths)
                queued += length;
            CHECK(r.stats.camera_rays == samples);
            CHECK(totals(r.profiler, Stage::Generate).items == samples);
            CHECK(totals(r.profiler, Stage::Accumulate).items == samples);
            CHECK(totals(r.profiler, Stage::Intersect).items == queued);
            CHECK(totals(r.profiler, Stage::Shade).items == queued);
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
            CHECK(totals(r.profiler, Stage::Shadow).items == r.stats.shadow_rays);
            CHECK(r.film.min_samples() == spp);
            CHECK(r.film.total_samples() == samples);
            // Stage times are real and fit inside the wall time.
            CHECK(r.profiler.device_busy_seconds() > 0.0);
            CHECK(r.profiler.device_busy_seconds() <= r.stats.render_seconds);
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
    ProfiledRender r = profiled_render(scene, 16, true);
    CHECK(r.stats.camera_rays == 8u * 8u * 16u);
    CHECK(totals(r.profiler, Stage::Shadow).items == r.stats.camera_rays);
    CHECK(r.stats.shadow_rays == r.stats.camera_rays);
}

TEST_CASE("profile: regeneration changes the schedule, not the image") {
    Scene scene = small_hexroom(16, 16);
    ProfiledRender wave = profiled_render(scene, 8, false);
    ProfiledRender regen = profiled_render(scene, 8, true);
    // Same samples, summed in a different order of flushes.
    Image a = wave.film.mean(), b = regen.film.mean();
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        REQUIRE(a.rgb[i] == Approx(b.rgb[i]).epsilon(1e-5).margin(1e-6));
    // Refilling keeps queues full: fewer, fuller launches.
    CHECK(regen.stats.iterations < wave.stats.iterations);
    CHECK(totals(regen.profiler, Stage::Intersect).items ==
          totals(wave.profiler, Stage::Intersect).items);
}

TEST_CASE("profile: the JSON and the trace parse, one trace event per launch") {
    ProfiledRender r = profiled_render(small_hexroom(8, 8), 2, true);
    ProfileContext context;
    context.device = profiling_device().info.name;
    context.scene = "hexroom";
    context.width = context.height = 8;
    context.spp = 2;
    context.build_options = "-D X=1";
    auto dir =
        std::filesystem::temp_directory_path() / ("wavepath-profile-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    write_profile_json(dir / "p.json", r.profiler, r.stats, context);
    r.profiler.write_trace(dir / "t.json", context.device);

    nlohmann::json profile = nlohmann::json::parse(std::ifstream(dir / "p.json"));
    CHECK(profile["device"] == context.device);
    CHECK(profile["spp"] == 2);
    CHECK(profile["build_options"] == "-D X=1");
    double stage_sum = 0.0;
    std::uint64_t launches = 0;
    for (const auto& stage : profile["stages"]) {
        stage_sum += stage["device_seconds"].get<double>();
        launches += stage["launches"].get<std::uint64_t>();
    }
    CHECK(stage_sum <= profile["wall_seconds"].get<double>());
    CHECK(profile["rays"]["camera"] == 8 * 8 * 2);

    nlohmann::json trace = nlohmann::json::parse(std::ifstream(dir / "t.json"));
    std::uint64_t complete_events = 0;
    for (const auto& event : trace["traceEvents"])
        if (event["ph"] == "X") {
            ++complete_events;
            CHECK(event["dur"].get<double>() >= 0.0);
        }
    CHECK(complete_events == launches);
    CHECK(complete_events == r.profiler.records().size());
    std::filesystem::remove_all(dir);
}

TEST_CASE("render: requests whose task counts would wrap 32 bits are split") {
    // 4096 x 4096 on 16 slots: each slot owns 2^20 pixels, so 4096 samples
    // would be 2^32 tasks; one call may hold at most 4095.
    CHECK(WavefrontIntegrator::max_samples_per_call(4096ull * 4096, 16) == 4095u);
    CHECK(WavefrontIntegrator::max_samples_per_call(800ull * 800, 800ull * 800) == 0xffffffffu);
    // Splitting is invisible: a small pool renders the same image.
    Scene scene = small_hexroom(9, 7);
    ProfiledRender full = profiled_render(scene, 3, false);
    ProfiledRender tiny = profiled_render(scene, 3, false, 5);
    Image a = full.film.mean(), b = tiny.film.mean();
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        REQUIRE(a.rgb[i] == Approx(b.rgb[i]).epsilon(1e-5).margin(1e-6));
}
