// `wavepath bench`: fixed workloads that print throughput figures.
//
// Never run as a test (timings on a shared 2-core machine are noise for a
// pass/fail check); later issues quote its output.
#include <cstdio>
#include <random>

#include <CLI/CLI.hpp>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "cl/context.hpp"
#include "cl/memory_bandwidth.hpp"
#include "render/wavefront.hpp"
#include "report/profile_report.hpp"
#include "scene/instancing.hpp"
#include "scene/load.hpp"

namespace wp {
namespace {

// Random rays: origins uniform in the scene's bounding box (shrunk by 1 %),
// directions uniform on the sphere; w of the direction is a segment length
// for shadow rays.
void random_rays(const Scene& scene, std::size_t count, std::uint32_t seed,
                 std::vector<cl_float4>& origins, std::vector<cl_float4>& directions) {
    glm::dvec3 lo(1e30), hi(-1e30);
    for (const Triangle& t : scene.triangles)
        for (const glm::dvec3& v : t.v) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    for (const Instance& instance : scene.instances) {
        const DoubleBox b =
            mapped_box(group_box(scene.shape_groups[instance.group]), instance.to_world);
        if (!b.empty()) {
            lo = glm::min(lo, b.lower);
            hi = glm::max(hi, b.upper);
        }
    }
    glm::dvec3 centre = 0.5 * (lo + hi), half = 0.495 * (hi - lo);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> normal;
    origins.resize(count);
    directions.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        glm::dvec3 o = centre + half * glm::dvec3(u(rng), u(rng), u(rng));
        glm::dvec3 d = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
        double length = 5.0 * (u(rng) + 1.0);
        origins[i] = {
            {static_cast<float>(o.x), static_cast<float>(o.y), static_cast<float>(o.z), 0.f}};
        directions[i] = {{static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z),
                          static_cast<float>(length)}};
    }
}

void render_workload(DeviceContext& device, const Scene& scene, std::uint32_t spp,
                     IntegratorOptions options, bool regeneration, const std::string& name) {
    options.regeneration = regeneration;
    WavefrontIntegrator integrator(device, scene, options);
    Profiler profiler;
    integrator.set_profiler(&profiler);
    Film film(scene.camera.width, scene.camera.height);
    integrator.render(0, spp, film);
    ProfileContext context;
    context.device = device.info.name;
    context.scene = name;
    context.width = scene.camera.width;
    context.height = scene.camera.height;
    context.spp = spp;
    context.build_options = integrator.program().options;
    context.build_seconds = integrator.program().build_seconds;
    context.regeneration = regeneration;
    context.pool_size = integrator.pool_size();
    context.memory_bandwidth = measured_copy_bandwidth(device);
    std::printf("%s\n", profile_table(profiler, integrator.stats(), context).c_str());
}

} // namespace

CLI::App* add_bench_subcommand(CLI::App& app, BenchCommand& command) {
    CLI::App* b = app.add_subcommand(
        "bench", "Print throughput figures for fixed workloads: a render of the scene with and "
                 "without path regeneration, and each tracing stage alone on 2^20 random rays");
    b->add_option("scene", command.scene, "Scene file")->capture_default_str();
    add_scene_options(*b);
    add_device_option(*b, command.device);
    b->add_option("--size", command.size, "Rendered workload: size x size pixels")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    b->add_option("--spp", command.spp, "Rendered workload: samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1u, 4096u));
    b->add_option("--repetitions", command.repetitions, "Launches per stage-alone workload")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    add_integrator_options(*b, command.integrator);
    // The workload is rendered both ways, so a choice would be ignored.
    b->remove_option(b->get_option("--regeneration"));
    return b;
}

int run_bench(const BenchCommand& command) {
    DeviceContext device(select_device(command.device), true);
    Scene scene = load_scene(command.scene, scene_read_options());
    std::printf("wavepath bench on %s (%s)\n\n", device.info.name.c_str(),
                device.info.driver_version.c_str());

    scene.camera.width = scene.camera.height = command.size;
    for (bool regeneration : {true, false})
        render_workload(device, scene, command.spp, command.integrator, regeneration,
                        command.scene);

    // Each tracing stage alone on a full synthetic queue.
    const std::size_t rays = std::size_t{1} << 20;
    scene.camera.width = scene.camera.height = 1024; // a pool of 2^20 slots
    IntegratorOptions stage_alone = command.integrator;
    stage_alone.pool_size = 0; // one slot per ray
    WavefrontIntegrator integrator(device, scene, stage_alone);
    std::vector<cl_float4> origins, directions;
    random_rays(scene, rays, 1, origins, directions);
    const int repetitions = command.repetitions;
    double intersect = integrator.time_intersect(origins, directions, repetitions);
    double shadow = integrator.time_shadow(origins, directions, repetitions);
    const double traced = static_cast<double>(rays) * repetitions;
    std::printf("stage alone, %zu random rays in %s, %d repetitions:\n", rays,
                command.scene.c_str(), repetitions);
    std::printf("  intersect (closest hit): %8.3f Mrays/s  (%.1f ms per launch)\n",
                traced / intersect / 1e6, intersect / repetitions * 1e3);
    std::printf("  shadow (any hit):        %8.3f Mrays/s  (%.1f ms per launch)\n",
                traced / shadow / 1e6, shadow / repetitions * 1e3);
    return 0;
}

} // namespace wp
