// Shade sorted by material (--shade-order sorted, kernels/shade_sort.cl):
// the stages plan's shade takes its rays in the order of the material kind
// they hit instead of the order intersect left them in. Every slot's work
// depends only on its own state and its own counter-based random numbers,
// and a pixel's samples reach the film in the same batches whatever the
// order within an iteration, so the two orders must give the same image bit
// for bit and the same counts. A slot lost or shaded twice by the sort would
// change both. (The sort itself against a host reference:
// tests/kernels/test_shade_sort.cpp.)
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "scene/load.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

struct OrderRender {
    Film film;
    RenderStats stats;
};

OrderRender render_in_order(const Scene& scene, ShadeOrder order, IntegratorOptions options,
                            std::uint32_t spp) {
    options.seed = 5;
    options.launch_plan = LaunchPlan::Stages;
    options.shade_order = order;
    // Sorted shading runs no tail kernel (kernels/tail.cl), which would make
    // the tail of each wave one launch in arrival order: the queue lengths
    // below are compared iteration by iteration.
    options.tail_rays = 0;
    WavefrontIntegrator integrator(test::device(), scene, options);
    REQUIRE(integrator.launch_plan().sorted_shading == (order == ShadeOrder::Sorted));
    OrderRender out{Film(scene.camera.width, scene.camera.height), {}};
    integrator.render(0, spp, out.film);
    out.stats = integrator.stats();
    return out;
}

std::size_t differing_values(const Image& a, const Image& b) {
    REQUIRE(a.rgb.size() == b.rgb.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
        differing += a.rgb[i] != b.rgb[i] ? 1 : 0;
    return differing;
}

void check_same_render(const OrderRender& arrival, const OrderRender& sorted) {
    CHECK(arrival.stats.camera_rays == sorted.stats.camera_rays);
    CHECK(arrival.stats.bounce_rays == sorted.stats.bounce_rays);
    CHECK(arrival.stats.shadow_rays == sorted.stats.shadow_rays);
    CHECK(arrival.stats.capped_paths == sorted.stats.capped_paths);
    CHECK(arrival.stats.queue_lengths == sorted.stats.queue_lengths);
    CHECK(arrival.film.sums().count == sorted.film.sums().count);
    CHECK(differing_values(arrival.film.mean(), sorted.film.mean()) == 0);
    CHECK(differing_values(arrival.film.variance_of_mean(), sorted.film.variance_of_mean()) == 0);
    CHECK(differing_values(arrival.film.half_mean(1), sorted.film.half_mean(1)) == 0);
}

} // namespace

TEST_CASE("Shade order: sorted by material, the hexroom's image is arrival order's bit for bit",
          "[render][shade-order]") {
    const Scene scene = test::hexroom(20, 16);
    IntegratorOptions regenerating;
    regenerating.regeneration = true;
    regenerating.pool_size = 37;
    IntegratorOptions capped;
    capped.max_depth = 2;
    for (const IntegratorOptions& options : {IntegratorOptions{}, regenerating, capped}) {
        INFO("pool " << options.pool_size << ", max depth " << options.max_depth);
        const OrderRender arrival = render_in_order(scene, ShadeOrder::Arrival, options, 6);
        const OrderRender sorted = render_in_order(scene, ShadeOrder::Sorted, options, 6);
        REQUIRE(arrival.film.min_samples() == 6);
        check_same_render(arrival, sorted);
    }
}

TEST_CASE("Shade order: sorted by material, the showcase's image (eight material kinds, "
          "textures, an environment map) is arrival order's bit for bit",
          "[render][shade-order]") {
    Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/materials/showcase.json");
    scene.camera.width = 24;
    scene.camera.height = 20;
    const OrderRender arrival = render_in_order(scene, ShadeOrder::Arrival, {}, 3);
    const OrderRender sorted = render_in_order(scene, ShadeOrder::Sorted, {}, 3);
    REQUIRE(arrival.stats.bounce_rays > 0);
    check_same_render(arrival, sorted);
}

TEST_CASE("Shade order: sorted by material, the instances' image (materials of the shape groups' "
          "triangles) is arrival order's bit for bit",
          "[render][shade-order]") {
    Scene scene =
        load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/mitsuba/instances.xml");
    scene.camera.width = 16;
    scene.camera.height = 12;
    const OrderRender arrival = render_in_order(scene, ShadeOrder::Arrival, {}, 2);
    const OrderRender sorted = render_in_order(scene, ShadeOrder::Sorted, {}, 2);
    REQUIRE(arrival.stats.bounce_rays > 0);
    check_same_render(arrival, sorted);
}

TEST_CASE("Shade order: auto is arrival on a CPU, sorted makes auto pick the stages plan, a fused "
          "plan shades in arrival order and refuses sorted",
          "[launch-plan][shade-order]") {
    DeviceInfo cpu, gpu;
    cpu.type = "CPU";
    gpu.type = "GPU";
    for (bool vectorised : {false, true}) {
        const ChosenLaunchPlan on_cpu = choose_launch_plan(LaunchPlan::Auto, cpu, vectorised);
        CHECK_FALSE(on_cpu.sorted_shading);
        CHECK_FALSE(on_cpu.shade_order_why.empty());
        for (const DeviceInfo& device : {cpu, gpu}) {
            const ChosenLaunchPlan sorted = choose_launch_plan(LaunchPlan::Auto, device, vectorised,
                                                               std::nullopt, ShadeOrder::Sorted);
            CHECK(sorted.plan == LaunchPlan::Stages);
            CHECK(sorted.sorted_shading);
            CHECK(sorted.shade_order_why.find("asked for") == 0);
            CHECK_FALSE(choose_launch_plan(LaunchPlan::Stages, device, vectorised, std::nullopt,
                                           ShadeOrder::Arrival)
                            .sorted_shading);
            for (LaunchPlan fused : {LaunchPlan::Bounce, LaunchPlan::Wave}) {
                CHECK_FALSE(choose_launch_plan(fused, device, vectorised).sorted_shading);
                CHECK_THROWS_AS(
                    choose_launch_plan(fused, device, vectorised, std::nullopt, ShadeOrder::Sorted),
                    std::runtime_error);
            }
        }
    }
}
