// libFuzzer target: bytes as a mesh file, through parse_mesh (scene/mesh.hpp),
// the in-memory form of load_mesh: the OBJ or PLY reader, triangulation, the
// degenerate-triangle filter and normals. Built twice, as obj_fuzzer and
// ply_fuzzer; WAVEPATH_FUZZ_MESH_NAME ("fuzz.obj" or "fuzz.ply") picks the
// reader by its extension; serialized_fuzzer ("fuzz.serialized") reads
// Mitsuba's zlib-compressed meshes.
//
// The triangles' `usemtl` names are then matched against scene materials
// (resolve_materials), as the scene loader does. Each input is read twice, to
// reach both halves of the loader: once keeping the file's normals with the
// identity transform, once computing smooth normals under a mirroring
// transform (which reverses every triangle's winding); the second asks for
// mesh 1, which sends a .serialized file through its end-of-file dictionary
// (other formats have one mesh and ignore the index).
//
// A MeshError with a clean one-line message (clean_error.hpp) is the expected
// answer to bad input, and warnings must be clean too; anything else is a
// finding (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "clean_error.hpp"
#include "scene/mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    wp::MeshLoadOptions file_normals;
    file_normals.normals = wp::NormalSource::File;
    wp::MeshLoadOptions smooth_mirrored;
    smooth_mirrored.normals = wp::NormalSource::Smooth;
    smooth_mirrored.transform = wp::Transform::scale(glm::dvec3(-1.0, 2.0, 0.5));
    smooth_mirrored.shape_index = 1;
    // The scene's materials that `usemtl` names are matched against, as the
    // scene loader does; names in the seeds ("red", "blue") and others.
    static const std::vector<wp::Material> scene_materials = {{"white"}, {"red"}, {"blue"}};
    for (const wp::MeshLoadOptions& options : {file_normals, smooth_mirrored}) {
        try {
            const wp::TriangleMesh mesh = wp::parse_mesh(bytes, WAVEPATH_FUZZ_MESH_NAME, options);
            std::vector<std::string> warnings = mesh.warnings;
            const std::vector<std::uint32_t> materials =
                wp::resolve_materials(mesh, scene_materials, 0, warnings);
            if (materials.size() != mesh.triangles.size())
                std::abort();
            for (const std::string& warning : warnings)
                wp::fuzz::require_clean_message(warning, "a mesh warning");
        } catch (const wp::MeshError& error) {
            wp::fuzz::require_clean_message(error.what(), "a MeshError");
        }
    }
    return 0;
}
