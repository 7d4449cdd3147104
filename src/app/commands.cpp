#include "app/commands.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/progress.hpp"
#include "cl/context.hpp"
#include "cl/device.hpp"
#include "image/image_io.hpp"
#include "render/wavefront.hpp"
#include "scene/load.hpp"

namespace wp {
namespace {

// Fails before rendering, not after, if an output cannot be written.
void check_output_path(const std::string& path) {
    if (path.empty())
        return;
    std::filesystem::path p(path);
    std::string extension = p.extension().string();
    for (char& c : extension)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".exr" && extension != ".pfm" && extension != ".png")
        throw ImageError("cannot write '" + path + "': unsupported image extension '" +
                         p.extension().string() + "' (use .exr, .pfm or .png)");
    std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : ".";
    if (!std::filesystem::is_directory(dir))
        throw ImageError("cannot write '" + path + "': directory '" + dir.string() +
                         "' does not exist");
}

} // namespace

int run_devices() {
    std::vector<DeviceInfo> devices = list_devices();
    if (devices.empty()) {
        std::cerr << "wavepath: no OpenCL device found (is an ICD such as pocl-opencl-icd "
                     "installed?)\n";
        return 1;
    }
    std::cout << describe_devices(devices);
    return 0;
}

int run_render(const RenderCommand& command) {
    check_output_path(command.out);
    check_output_path(command.png);

    Scene scene = load_scene(command.scene);
    for (const std::string& warning : scene.warnings)
        std::cerr << "wavepath: warning: " << warning << "\n";
    if (command.width > 0)
        scene.camera.width = command.width;
    if (command.height > 0)
        scene.camera.height = command.height;

    DeviceContext device(select_device(command.device));
    IntegratorOptions options;
    options.seed = command.seed;
    options.max_depth = command.max_depth;
    options.general_kernels = command.general;
    WavefrontIntegrator integrator(device, scene, options);

    std::cerr << "wavepath: " << scene.camera.width << "x" << scene.camera.height << " at "
              << command.spp << " spp on " << device.info.name << " (kernels built in "
              << integrator.program().build_seconds
              << " s; features: " << integrator.features().describe() << ")\n";

    Film film(scene.camera.width, scene.camera.height);
    const std::uint64_t pixels = static_cast<std::uint64_t>(scene.camera.width) *
                                 static_cast<std::uint64_t>(scene.camera.height);
    {
        ProgressBar progress(command.spp, pixels);
        integrator.render(0, command.spp, film, [&](std::uint32_t done) { progress.update(done); });
    }

    Image image = film.mean();
    write_image(command.out, image, command.view);
    if (!command.png.empty())
        write_image(command.png, image, command.view);

    const RenderStats& stats = integrator.stats();
    double seconds = stats.render_seconds;
    double samples = static_cast<double>(pixels) * command.spp;
    double rays = static_cast<double>(stats.camera_rays + stats.bounce_rays + stats.shadow_rays);
    std::printf("rendered %s: %dx%d, %u spp, %.2f s, %.3g samples/s, %.3g Mrays/s "
                "(%.0f camera, %.0f bounce, %.0f shadow rays)\n",
                command.out.c_str(), scene.camera.width, scene.camera.height, command.spp, seconds,
                samples / seconds, rays / seconds / 1e6, static_cast<double>(stats.camera_rays),
                static_cast<double>(stats.bounce_rays), static_cast<double>(stats.shadow_rays));
    std::printf("paths cut by the depth cap (%u): %llu; NaN/Inf samples dropped: %llu\n",
                command.max_depth, static_cast<unsigned long long>(stats.capped_paths),
                static_cast<unsigned long long>(stats.nonfinite_samples));
    return 0;
}

} // namespace wp
