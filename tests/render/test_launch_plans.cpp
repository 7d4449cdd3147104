// Launch plans (render/wavefront.hpp, docs/architecture.md "Launch plans"):
// the stage kernels, intersect+shade+shadow fused per bounce, and one
// megakernel per wave must render the same image.
//
// Every plan runs the same stage functions (kernels/*.cl) in the same order
// for each path, and the random numbers are a function of (seed, pixel,
// sample, depth, dimension), so each sample's radiance is the same float
// value in every plan. What may differ is only where the device's float32
// film batches end (render/film.hpp): the stages and bounce plans fold the
// film every 32 iterations, the wave plan every 8 tasks per slot; a pixel's
// samples summed in float32 in other groups round differently. So:
//  - sample counts, ray counts and film sums of whole batches agree exactly;
//  - stages and bounce (the same host loop, the same batches) agree bit for bit;
//  - wave agrees bit for bit when every batch holds one sample per pixel
//    (one sample per render call, as the CLI renders without regeneration);
//  - otherwise wave agrees within the float32 rounding of the batch sums:
//    a sum of k non-negative terms in float32 is off by at most
//    (k - 1) 2^-24 of the sum (one rounding per addition), each of the two
//    renders may be so off, with k <= 16 here: a relative 32 x 2^-24.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "support/render_helpers.hpp"

using namespace wp;

namespace {

struct PlanRender {
    Film film;
    RenderStats stats;
};

// `spp` samples in calls of `per_call` (the CLI's split), seed 3.
PlanRender render_plan(const Scene& scene, LaunchPlan plan, IntegratorOptions options,
                       std::uint32_t spp, std::uint32_t per_call) {
    options.seed = 3;
    options.launch_plan = plan;
    WavefrontIntegrator integrator(test::device(), scene, options);
    REQUIRE(integrator.launch_plan().plan == plan);
    PlanRender out{Film(scene.camera.width, scene.camera.height), {}};
    for (std::uint32_t done = 0; done < spp; done += per_call)
        integrator.render(done, std::min(per_call, spp - done), out.film);
    out.stats = integrator.stats();
    return out;
}

// The largest |a - b| / max(|a|, |b|) over every pixel and channel (0 where
// both are 0), and whether any pixel differs at all.
struct Difference {
    double relative = 0.0;
    std::size_t differing = 0;
};

Difference compare(const Image& a, const Image& b) {
    REQUIRE(a.rgb.size() == b.rgb.size());
    Difference d;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double x = a.rgb[i], y = b.rgb[i];
        if (x == y)
            continue;
        ++d.differing;
        d.relative = std::max(d.relative, std::abs(x - y) / std::max(std::abs(x), std::abs(y)));
    }
    return d;
}

void check_same_counts(const PlanRender& a, const PlanRender& b) {
    CHECK(a.stats.camera_rays == b.stats.camera_rays);
    CHECK(a.stats.bounce_rays == b.stats.bounce_rays);
    CHECK(a.stats.shadow_rays == b.stats.shadow_rays);
    CHECK(a.stats.capped_paths == b.stats.capped_paths);
    CHECK(a.stats.nonfinite_samples == b.stats.nonfinite_samples);
    const FilmSums x = a.film.sums(), y = b.film.sums();
    CHECK(x.count == y.count);
    CHECK(x.odd_count == y.odd_count);
}

constexpr double kRoundingTolerance = 32.0 / 16777216.0; // 32 x 2^-24, see above

struct Variant {
    const char* name;
    IntegratorOptions options;
};

std::vector<Variant> variants() {
    std::vector<Variant> out;
    out.push_back({"default", {}});
    IntegratorOptions o;
    o.regeneration = true;
    o.pool_size = 37;
    out.push_back({"regeneration, pool 37", o});
    o = {};
    o.pool_size = 50; // several pixels a slot, one wave at a time
    out.push_back({"pool 50", o});
    o = {};
    o.next_event_estimation = false;
    o.sampler = Sampler::Independent;
    out.push_back({"no NEE, independent sampler", o});
    o = {};
    o.diffuse_sampling = DiffuseSampling::Report;
    o.light_sampling = LightSampling::SolidAngle;
    o.general_kernels = true;
    out.push_back({"report, solid angle, general kernels", o});
    o = {};
    o.max_depth = 2;
    out.push_back({"max depth 2 (capped paths)", o});
    o = {};
    o.roulette_rule = RouletteRule::Mitsuba;
    o.roulette_depth = 2;
    out.push_back({"Mitsuba's roulette rule from bounce 2", o});
    o = {};
    o.roulette_rule = RouletteRule::Relative; // carries the first bounce's throughput in .w
    out.push_back({"the relative roulette rule", o});
    return out;
}

} // namespace

TEST_CASE("Launch plans: bounce renders the stages plan's image bit for bit, wave within the "
          "float32 rounding of the film batches, with the same counts",
          "[render][launch-plan]") {
    const Scene scene = test::hexroom(20, 16);
    for (const Variant& v : variants()) {
        INFO(v.name);
        const std::uint32_t spp = 6;
        const PlanRender stages = render_plan(scene, LaunchPlan::Stages, v.options, spp, spp);
        const PlanRender bounce = render_plan(scene, LaunchPlan::Bounce, v.options, spp, spp);
        const PlanRender wave = render_plan(scene, LaunchPlan::Wave, v.options, spp, spp);
        REQUIRE(stages.film.min_samples() == spp);
        check_same_counts(stages, bounce);
        check_same_counts(stages, wave);
        CHECK(compare(stages.film.mean(), bounce.film.mean()).differing == 0);
        CHECK(compare(stages.film.variance_of_mean(), bounce.film.variance_of_mean()).differing ==
              0);
        const Difference mean = compare(stages.film.mean(), wave.film.mean());
        INFO("wave vs stages: " << mean.differing << " values differ, at most by a relative "
                                << mean.relative);
        CHECK(mean.relative <= kRoundingTolerance);
        CHECK(compare(stages.film.half_mean(1), wave.film.half_mean(1)).relative <=
              kRoundingTolerance);
    }
}

TEST_CASE("Launch plans: one sample per render call (the CLI without regeneration), every plan's "
          "image is the stages plan's bit for bit",
          "[render][launch-plan]") {
    const Scene scene = test::hexroom(24, 20);
    const std::uint32_t spp = 5;
    const PlanRender stages = render_plan(scene, LaunchPlan::Stages, {}, spp, 1);
    for (LaunchPlan plan : {LaunchPlan::Bounce, LaunchPlan::Wave}) {
        INFO(to_string(plan));
        const PlanRender other = render_plan(scene, plan, {}, spp, 1);
        check_same_counts(stages, other);
        CHECK(compare(stages.film.mean(), other.film.mean()).differing == 0);
        CHECK(compare(stages.film.variance_of_mean(), other.film.variance_of_mean()).differing ==
              0);
        CHECK(compare(stages.film.half_mean(0), other.film.half_mean(0)).differing == 0);
    }
}

TEST_CASE("Launch plans: a Mitsuba file's max_depth renders the stages plan's image bit for bit "
          "in every plan, with and without next-event estimation through mirrors",
          "[render][launch-plan][mitsuba]") {
    // max_depth 3 (DepthRule::PathLength): the last vertex adds its emission
    // and ends the path, the mirror's light sample is made only at the first
    // vertex (kernels/shade.cl). One sample per render call, as above.
    SceneReadOptions read;
    read.defines = {{"max_depth", "3"}};
    const Scene scene = load_scene(WAVEPATH_SOURCE_DIR "/tests/data/mitsuba/max-depth.xml", read);
    const std::uint32_t spp = 4;
    std::uint64_t shadow_rays[2] = {0, 0};
    for (bool mirror_next_event : {false, true}) {
        IntegratorOptions options;
        options.mirror_next_event = mirror_next_event;
        const PlanRender stages = render_plan(scene, LaunchPlan::Stages, options, spp, 1);
        CHECK(stages.stats.capped_paths == 0);
        shadow_rays[mirror_next_event] = stages.stats.shadow_rays;
        for (LaunchPlan plan : {LaunchPlan::Bounce, LaunchPlan::Wave}) {
            INFO(to_string(plan) << ", mirror next-event estimation " << mirror_next_event);
            const PlanRender other = render_plan(scene, plan, options, spp, 1);
            check_same_counts(stages, other);
            CHECK(compare(stages.film.mean(), other.film.mean()).differing == 0);
            CHECK(
                compare(stages.film.variance_of_mean(), other.film.variance_of_mean()).differing ==
                0);
        }
    }
    CHECK(shadow_rays[1] > shadow_rays[0]); // the mirror's light samples were made
}

TEST_CASE("Launch plans: a wave's tail traced in one launch (kernels/tail.cl) renders the stages "
          "plan's image bit for bit, with the same counts and rays per bounce",
          "[render][launch-plan][tail]") {
    // The tail kernel runs the stage functions in the stage kernels' order
    // per bounce, and stops where the host would fold the film (every 32
    // iterations on a CPU), so that each path ends in the film batch it ends
    // in without it: with several samples per call (several waves, whose
    // samples of a pixel share float32 batches) a tail that ran across a
    // fold would change the rounding. 320 slots; thresholds from a few rays
    // to the whole pool (every wave traced by the tail kernel alone, its
    // camera rays included).
    const Scene scene = test::hexroom(20, 16);
    const std::uint32_t spp = 6;
    IntegratorOptions pool50;
    pool50.pool_size = 50; // several pixels a slot: folds fall inside tails
    IntegratorOptions no_nee;
    no_nee.next_event_estimation = false;
    IntegratorOptions capped;
    capped.max_depth = 2;
    IntegratorOptions general;
    general.diffuse_sampling = DiffuseSampling::Report;
    general.light_sampling = LightSampling::SolidAngle;
    general.general_kernels = true;
    IntegratorOptions no_mirror_nee; // the hexroom's default has mirror NEE's two-leg rays
    no_mirror_nee.mirror_next_event = false;
    const std::pair<const char*, IntegratorOptions> cases[] = {
        {"default", {}},         {"pool 50", pool50},          {"no NEE", no_nee},
        {"max depth 2", capped}, {"report, general", general}, {"no mirror NEE", no_mirror_nee}};
    for (const auto& [name, options] : cases)
        for (std::uint32_t per_call : {spp, 1u}) {
            // One sample a call (the CLI's) for the first two: a call is a wave.
            if (per_call == 1 && &options != &cases[0].second && &options != &cases[1].second)
                continue;
            INFO(name << ", " << per_call << " samples a call");
            IntegratorOptions off = options;
            off.tail_rays = 0;
            const PlanRender reference = render_plan(scene, LaunchPlan::Stages, off, spp, per_call);
            if (options.max_depth == 2)
                REQUIRE(reference.stats.capped_paths > 0);
            for (std::uint32_t tail : {3u, 40u, 320u})
                for (LaunchPlan plan : {LaunchPlan::Stages, LaunchPlan::Bounce}) {
                    if (plan == LaunchPlan::Bounce && tail != 40)
                        continue; // the same host loop; once is enough
                    INFO("tail from " << tail << " rays, " << to_string(plan));
                    IntegratorOptions on = options;
                    on.tail_rays = tail;
                    const PlanRender other = render_plan(scene, plan, on, spp, per_call);
                    // The tail kernel ran (from the whole pool it must;
                    // from a few rays, when a wave drains that far).
                    CHECK(other.stats.iterations <= reference.stats.iterations);
                    if (tail == 320)
                        CHECK(other.stats.iterations < reference.stats.iterations);
                    check_same_counts(reference, other);
                    CHECK(other.stats.rays_per_bounce == reference.stats.rays_per_bounce);
                    CHECK(compare(reference.film.mean(), other.film.mean()).differing == 0);
                    CHECK(compare(reference.film.variance_of_mean(), other.film.variance_of_mean())
                              .differing == 0);
                    CHECK(compare(reference.film.half_mean(1), other.film.half_mean(1)).differing ==
                          0);
                }
        }
}

TEST_CASE("Launch plans: the tail's threshold is the option's, at most a sixteenth of the pool by "
          "default and none for a small pool, and off with regeneration, sorted shading and in "
          "the wave plan",
          "[launch-plan][tail]") {
    CHECK(tail_rays_for(std::nullopt, 65536) == kDefaultTailRays);
    CHECK(tail_rays_for(std::nullopt, kTailMinimumPool) == kTailMinimumPool / 16);
    CHECK(tail_rays_for(std::nullopt, kTailMinimumPool - 1) == 0);
    CHECK(tail_rays_for(std::nullopt, 320) == 0);
    CHECK(tail_rays_for(20u, 320) == 20);
    CHECK(tail_rays_for(0u, 65536) == 0);
    CHECK(tail_rays_for(100000u, 320) == 100000);
    // WAVEPATH_TAIL_RAYS overrides both, and a value that is not a count is
    // refused by name rather than read as 0 (no tail).
    ::setenv("WAVEPATH_TAIL_RAYS", "7", 1);
    CHECK(tail_rays_for(100000u, 320) == 7);
    for (const char* bad : {"", "x", "12x", "-3", "99999999999"}) {
        ::setenv("WAVEPATH_TAIL_RAYS", bad, 1);
        CHECK_THROWS_WITH(tail_rays_for(std::nullopt, 65536),
                          Catch::Matchers::Contains("WAVEPATH_TAIL_RAYS"));
    }
    ::unsetenv("WAVEPATH_TAIL_RAYS");
    const Scene scene = test::hexroom(20, 16);
    IntegratorOptions options;
    options.tail_rays = 40;
    options.launch_plan = LaunchPlan::Stages;
    CHECK(WavefrontIntegrator(test::device(), scene, options).tail_rays() == 40);
    options.launch_plan = LaunchPlan::Bounce;
    CHECK(WavefrontIntegrator(test::device(), scene, options).tail_rays() == 40);
    options.launch_plan = LaunchPlan::Wave;
    CHECK(WavefrontIntegrator(test::device(), scene, options).tail_rays() == 0);
    options.launch_plan = LaunchPlan::Stages;
    options.regeneration = true;
    CHECK(WavefrontIntegrator(test::device(), scene, options).tail_rays() == 0);
    options.regeneration = false;
    options.shade_order = ShadeOrder::Sorted;
    CHECK(WavefrontIntegrator(test::device(), scene, options).tail_rays() == 0);
}

TEST_CASE("Shade's work-group compaction of its queue pushes: the image and the counts do not "
          "depend on the work-group size",
          "[render][launch-plan]") {
    // The stages plan's shade numbers each work-group's pushes in local
    // memory and reserves every queue's range with one atomic per group
    // (kernels/shade.cl). A slot lost or queued twice would change the image
    // or the ray counts; sizes past WP_MAX_WORK_GROUP_SIZE must be clamped to
    // it by the host (the local arrays hold no more). 20x16 pixels: 320
    // slots, several groups of each size, the last one partly surplus.
    const Scene scene = test::hexroom(20, 16);
    const std::uint32_t spp = 4;
    IntegratorOptions capped;
    capped.max_depth = 2;
    for (const IntegratorOptions& options : {IntegratorOptions{}, capped}) {
        INFO("max depth " << options.max_depth);
        const PlanRender reference = render_plan(scene, LaunchPlan::Stages, options, spp, spp);
        if (options.max_depth == 2)
            REQUIRE(reference.stats.capped_paths > 0);
        for (const char* size : {"1", "7", "256", "1000"}) {
            INFO("work-group size " << size);
            REQUIRE(setenv("WAVEPATH_WORK_GROUP_SIZE", size, 1) == 0);
            const PlanRender other = render_plan(scene, LaunchPlan::Stages, options, spp, spp);
            unsetenv("WAVEPATH_WORK_GROUP_SIZE");
            check_same_counts(reference, other);
            CHECK(compare(reference.film.mean(), other.film.mean()).differing == 0);
            CHECK(compare(reference.film.variance_of_mean(), other.film.variance_of_mean())
                      .differing == 0);
        }
    }
}

TEST_CASE("Launch plans: progress reaches the samples asked for in every plan",
          "[render][launch-plan]") {
    const Scene scene = test::hexroom(16, 16);
    for (LaunchPlan plan : {LaunchPlan::Stages, LaunchPlan::Bounce, LaunchPlan::Wave})
        for (bool regeneration : {false, true}) {
            INFO(to_string(plan) << (regeneration ? " with regeneration" : ""));
            IntegratorOptions options;
            options.launch_plan = plan;
            options.regeneration = regeneration;
            WavefrontIntegrator integrator(test::device(), scene, options);
            Film film(16, 16);
            double last = 0.0;
            bool monotonic = true;
            integrator.render(0, 9, film, [&](double spp) {
                monotonic = monotonic && spp >= last;
                last = spp;
            });
            CHECK(monotonic);
            CHECK(last == Approx(9.0));
            CHECK(film.min_samples() == 9);
        }
}

TEST_CASE("Launch plans: auto picks by device type and tracing kind, an explicit plan is kept",
          "[launch-plan]") {
    DeviceInfo cpu, gpu;
    cpu.type = "CPU";
    gpu.type = "GPU";
    CHECK(choose_launch_plan(LaunchPlan::Auto, cpu, true).plan == LaunchPlan::Stages);
    CHECK(choose_launch_plan(LaunchPlan::Auto, cpu, false).plan == LaunchPlan::Wave);
    for (bool vectorised : {false, true}) {
        CHECK(choose_launch_plan(LaunchPlan::Auto, gpu, vectorised).plan == LaunchPlan::Stages);
        CHECK_FALSE(choose_launch_plan(LaunchPlan::Auto, gpu, vectorised).why.empty());
        for (LaunchPlan plan : {LaunchPlan::Stages, LaunchPlan::Bounce, LaunchPlan::Wave}) {
            CHECK(choose_launch_plan(plan, cpu, vectorised).plan == plan);
            CHECK(choose_launch_plan(plan, gpu, vectorised).plan == plan);
        }
    }
}

TEST_CASE("Launch plans: regeneration and the film's folds by device type, an explicit choice "
          "is kept",
          "[launch-plan]") {
    DeviceInfo cpu, gpu;
    cpu.type = "CPU";
    gpu.type = "GPU";
    const ChosenLaunchPlan on_cpu = choose_launch_plan(LaunchPlan::Auto, cpu, true);
    const ChosenLaunchPlan on_gpu = choose_launch_plan(LaunchPlan::Auto, gpu, true);
    // The CPU plan as it was: one wave at a time, a sample per call.
    CHECK_FALSE(on_cpu.regeneration);
    CHECK(on_cpu.samples_per_call == 1);
    CHECK(on_cpu.iterations_per_flush == 32);
    // A GPU keeps its launches full and folds the film less often.
    CHECK(on_gpu.regeneration);
    CHECK(on_gpu.iterations_per_flush > on_cpu.iterations_per_flush);
    CHECK(on_gpu.samples_per_call > 8);
    CHECK(on_gpu.regeneration_why.find("auto") == 0);
    for (bool asked : {false, true})
        for (const DeviceInfo& device : {cpu, gpu}) {
            const ChosenLaunchPlan chosen =
                choose_launch_plan(LaunchPlan::Stages, device, true, asked);
            CHECK(chosen.regeneration == asked);
            CHECK(chosen.regeneration_why.find("asked for") == 0);
            // Without regeneration a call is one wave: one sample per pixel.
            CHECK((chosen.samples_per_call == 1) == !asked);
        }
}

TEST_CASE("Launch plans: on the test device, auto keeps the stages for the hexroom's specialised "
          "kernels and takes the wave for its hierarchy",
          "[launch-plan]") {
    if (test::device().info.type != "CPU") {
        WARN("skipped: the test device is not a CPU device");
        return;
    }
    const Scene scene = test::hexroom(8, 8);
    IntegratorOptions options;
    CHECK(WavefrontIntegrator(test::device(), scene, options).launch_plan().plan ==
          LaunchPlan::Stages);
    options.traversal = Traversal::Hierarchy;
    CHECK(WavefrontIntegrator(test::device(), scene, options).launch_plan().plan ==
          LaunchPlan::Wave);
}
