// A wavepath scene as a Mitsuba 3 scene (docs/mitsuba-export.md): one XML
// file with the camera, the integrator, the materials and the spheres, and
// beside it one binary PLY file per material holding that material's
// triangles. Rendering both should give the same image up to Monte Carlo
// noise, so a user can check one renderer against the other.
//
// Everything wavepath's scenes hold has an exact counterpart in Mitsuba but
// one: triangles with shading normals, which both renderers interpolate, but
// wavepath with its shadow-terminator fix and Mitsuba without. Those come
// with a warning (MitsubaExport::warnings), not an error, since the images
// differ only where the normals bend away from the facets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace wp {

struct MitsubaExportOptions {
    std::uint32_t sample_count = 64; // the `independent` sampler's samples per pixel
};

// One PLY file of the export: every triangle of one material, in the order
// of Scene::triangles, three vertices of its own each (no vertex is shared,
// so the file holds the scene's triangles exactly as they are).
struct MitsubaMesh {
    std::string file_name; // beside the XML, which names it by this relative path
    std::uint32_t material = 0;
    int group = -1; // the shape group whose triangles it holds; -1, the scene's own
    std::size_t triangle_count = 0;
    bool has_normals = false;       // vertex normals written (shading normals)
    std::vector<unsigned char> ply; // the whole file
};

struct MitsubaExport {
    std::string xml;
    std::vector<MitsubaMesh> meshes;
    std::vector<std::string> warnings; // approximations, one line each
};

// Mitsuba's `perspective` sensor for wavepath's pinhole camera. wavepath
// traces direction = normalize(forward + sx * right + sy * up) with sx, sy in
// [-1, 1] (sx to the image's right, sy to its top; device_scene.cpp), where
// forward is unit, right = normalize(cross(forward, camera.up)) * tan(fov/2)
// * aspect and up = cross(right, forward) unit * tan(fov/2). Mitsuba's sensor
// looks along `target - origin`, its image's right is -normalize(cross(up',
// dir)) = normalize(cross(dir, up')) and its top cross(dir, left), and the
// horizontal half-width at unit distance is tan(fov_x / 2); so origin = eye,
// up' = wavepath's unit up, fov_x = 2 atan(|right|) give the same rays.
struct MitsubaCamera {
    glm::dvec3 origin{0.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0};         // orthonormal to target - origin
    double fov_x_degrees = 0.0; // fov_axis "x": the full horizontal angle
    double near_clip = 0.0;     // wavepath has no clipping planes: these keep
    double far_clip = 0.0;      // all of the scene between them
};
MitsubaCamera mitsuba_camera(const Scene& scene);

// The scene as Mitsuba XML and PLY files, in memory. Each mesh's file name is
// `<mesh_prefix>-<n>-<material name, letters and digits only>.ply`.
MitsubaExport export_mitsuba(const Scene& scene, const std::string& mesh_prefix,
                             const MitsubaExportOptions& options = {});

// Where write_mitsuba puts the meshes: beside xml_path.
std::vector<std::filesystem::path> mitsuba_mesh_paths(const MitsubaExport& exported,
                                                      const std::filesystem::path& xml_path);

// Writes the meshes, then the XML, each atomically (util/file.hpp), so the XML
// never names a mesh that is missing or half-written. Throws FileError.
void write_mitsuba(const MitsubaExport& exported, const std::filesystem::path& xml_path);

} // namespace wp
