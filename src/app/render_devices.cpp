#include "app/render_devices.hpp"

#include <cstdio>

#include "app/cli_options.hpp"
#include "cl/device.hpp"
#include "render/prepared_scene.hpp"
#include "report/device_profile.hpp"
#ifdef WAVEPATH_HAVE_MPI
#include "mpi/mpi_render.hpp"
#include "scene/load.hpp"
#endif

namespace wp {

std::optional<int> run_render_as_mpi_worker(const RenderCommand& command) {
#ifdef WAVEPATH_HAVE_MPI
    MpiJob& job = MpiJob::get();
    if (job.size() > 1 && job.rank() != 0)
        return run_mpi_worker(
            job,
            [&] {
                Scene scene = load_scene(command.scene, scene_read_options());
                if (command.width > 0)
                    scene.camera.width = command.width;
                if (command.height > 0)
                    scene.camera.height = command.height;
                return scene;
            },
            command.device, command.integrator);
#else
    (void)command;
#endif
    return std::nullopt;
}

std::unique_ptr<MultiDeviceRenderer> open_renderer(const RenderCommand& command, Scene& scene,
                                                   bool profiling) {
#ifdef WAVEPATH_HAVE_MPI
    MpiJob& job = MpiJob::get();
    if (job.size() > 1)
        return open_mpi_renderer(job, scene, command.device, command.integrator, profiling);
#endif
    const std::vector<DeviceInfo> devices = select_devices(command.device);
    // Held here until every device has uploaded it (and after, by the
    // buffers of a device that uses its arrays in place), and freed with it
    // the scene's triangles, which nothing after this needs.
    const PreparedScene prepared = prepare_scene_releasing_triangles(scene, command.integrator);
    return std::make_unique<MultiDeviceRenderer>(devices, prepared, profiling);
}

std::vector<std::string> device_names(const MultiDeviceRenderer& renderer) {
    std::vector<std::string> names;
    for (const DeviceShare& share : renderer.shares())
        names.push_back(share.name);
    return names;
}

void print_device_shares(const MultiDeviceRenderer& renderer) {
    const std::vector<DeviceShare> shares = renderer.shares();
    if (shares.size() > 1)
        std::printf("%s", device_share_table(shares).c_str());
}

} // namespace wp
