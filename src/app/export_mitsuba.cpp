// `wavepath export-mitsuba`: the scene as a Mitsuba 3 scene, to check
// wavepath against another renderer (scene/mitsuba_export.hpp,
// docs/mitsuba-export.md).
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "scene/mitsuba_export.hpp"
#include "util/file.hpp"

namespace wp {

CLI::App* add_export_mitsuba_subcommand(CLI::App& app, ExportMitsubaCommand& command) {
    CLI::App* e = app.add_subcommand(
        "export-mitsuba", "Write the scene as a Mitsuba 3 XML scene, with its triangles as one "
                          "PLY file per material beside it (docs/mitsuba-export.md)");
    e->add_option("scene", command.scene, "Scene file (JSON)")->required();
    add_scene_options(*e);
    e->add_option("out", command.out, "The Mitsuba scene to write (.xml)")->required();
    e->add_option("--spp,-s", command.spp, "Samples per pixel of Mitsuba's sampler")
        ->capture_default_str()
        ->check(CLI::Range(1u, cli_limits::max_samples_per_pixel));
    add_image_size_options(*e, command.width, command.height);
    return e;
}

int run_export_mitsuba(const ExportMitsubaCommand& command) {
    check_output(command.out, {".xml"});
    check_distinct_outputs({{"the scene", command.scene}}, {{"the Mitsuba scene", command.out}});
    const Scene scene = load_scene_for_render(command.scene, command.width, command.height);

    const std::filesystem::path xml_path = command.out;
    MitsubaExportOptions options;
    options.sample_count = command.spp;
    const MitsubaExport exported = export_mitsuba(scene, xml_path.stem().string(), options);

    // Every mesh file too is checked before anything is written.
    std::vector<NamedPath> outputs = {{"the Mitsuba scene", command.out}};
    for (const std::filesystem::path& mesh : mitsuba_mesh_paths(exported, xml_path)) {
        check_output(mesh.string());
        outputs.push_back({"a mesh of the Mitsuba scene", mesh.string()});
    }
    check_distinct_outputs(scene_inputs(scene), outputs);

    for (const std::string& warning : exported.warnings)
        std::cerr << "wavepath: warning: " << warning << "\n";
    write_mitsuba(exported, xml_path);
    std::cout << "wrote " << command.out << " (" << scene.camera.width << "x" << scene.camera.height
              << ", " << command.spp << " spp) with " << exported.meshes.size() << " PLY mesh"
              << (exported.meshes.size() == 1 ? "" : "es") << " (" << scene.triangles.size()
              << " triangles) and " << scene.spheres.size() << " sphere"
              << (scene.spheres.size() == 1 ? "" : "s");
    if (!scene.instances.empty())
        std::cout << ", " << scene.shape_groups.size() << " shapegroup"
                  << (scene.shape_groups.size() == 1 ? "" : "s") << " and "
                  << scene.instances.size() << " instance"
                  << (scene.instances.size() == 1 ? "" : "s");
    std::cout << "\n";
    return 0;
}

} // namespace wp
