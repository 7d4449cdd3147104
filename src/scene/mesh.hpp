// Triangle meshes read from files: Wavefront OBJ (obj_reader.cpp, through
// Debian's tinyobjloader), PLY in ASCII and both binary byte orders
// (ply_reader.cpp) and Mitsuba's zlib-compressed .serialized
// (serialized_reader.cpp, through Debian's zlib). load_mesh() reads a file, triangulates its
// polygons and strips, drops degenerate triangles, applies the object's transform and, on request,
// computes smooth vertex normals. The result is an indexed mesh in double precision; turning it
// into scene triangles is the scene loader's job. Formats, options and every error message are
// described in docs/meshes.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.hpp"
#include "scene/transform.hpp"
#include "util/one_line.hpp"

namespace wp {

// Thrown for anything wrong with a mesh file. what() is one line that names the
// file and, where there is one, the place:
//   "bunny.obj:1207: face index 40000 out of range (35947 vertices)"   (text line)
//   "bunny.ply: face 12: file ends early (truncated?)"                 (PLY element, 0-based)
//   "missing.obj: cannot open mesh file: No such file or directory"    (whole file)
// Messages quote the file's bytes (a token that is not a number, a header line),
// so the constructor passes them through one_line (util/one_line.hpp): a carriage
// return, an escape or invalid UTF-8 in the file becomes '?'.
class MeshError : public std::runtime_error {
  public:
    explicit MeshError(const std::string& message) : std::runtime_error(one_line(message)) {}

    static MeshError in_file(const std::filesystem::path& file, const std::string& message);
    static MeshError at_line(const std::filesystem::path& file, std::size_t line,
                             const std::string& message);
    // element is the PLY element's name ("vertex", "face", "tristrips"), index 0-based.
    static MeshError at_element(const std::filesystem::path& file, const std::string& element,
                                std::size_t index, const std::string& message);
};

// Where a mesh's vertex normals come from.
enum class NormalSource {
    File,   // the file's normals when it has them for every vertex, else none
    Smooth, // computed: the area-weighted average of the adjacent face normals
    None,   // no vertex normals; shading uses the geometric normal
};

struct MeshLoadOptions {
    // Object-to-world transform, applied to positions and (by the inverse
    // transpose) to normals. A transform with negative determinant (a mirror)
    // also reverses every triangle's winding so that front faces stay front.
    Transform transform;
    NormalSource normals = NormalSource::File;
    // Keep the file's texture coordinates. An OBJ file's vertices are then
    // split along texture seams too, which a scene without textures has no
    // use for (and "smooth" normals would then differ across the seams).
    bool texture_coordinates = true;
    // Which mesh of a .serialized file, which may hold several (Mitsuba's
    // shape_index); other formats hold one and ignore it.
    std::uint32_t shape_index = 0;
};

// An indexed triangle mesh. Every triangle has a non-zero area (degenerate ones
// were dropped and counted) and its front face is the side of
// cross(p[b] - p[a], p[c] - p[a]), as for wp::Triangle.
struct TriangleMesh {
    std::string source; // the file it came from, for messages
    std::vector<glm::dvec3> positions;
    // Empty, or one unit-length normal per position.
    std::vector<glm::dvec3> normals;
    // Empty, or texture coordinates per position, Mitsuba's way: a PLY
    // file's (u, v) as they are, an OBJ file's vt as (u, 1 - v) (Mitsuba's
    // OBJ reader flips v so that an image's top row is at v = 0 for both).
    std::vector<glm::dvec2> uvs;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    // Material names in order of first use. Entry 0 is always "", meaning "the
    // object's own material": faces before any OBJ `usemtl`, and every PLY face.
    std::vector<std::string> material_names{""};
    // One entry per triangle: an index into material_names.
    std::vector<std::uint32_t> triangle_materials;

    std::size_t faces_read = 0;         // polygons and strip triangles in the file
    std::size_t dropped_degenerate = 0; // zero-area triangles that were dropped
    std::vector<std::string> warnings;  // one line each, naming the file

    bool has_normals() const { return !normals.empty(); }
};

// Reads the mesh file, choosing the format by extension (.obj, .ply or .serialized,
// any case).
// Throws MeshError for a missing or unreadable file, an unknown extension, and
// every problem listed in docs/meshes.md (bad indices, faces with fewer than three
// vertices, non-finite coordinates, coordinates beyond scene_limits::max_coordinate
// once transformed, truncated binary data, no faces left).
TriangleMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

// load_mesh on a file's bytes already in memory: `name` chooses the format (by
// its extension) and names the mesh in messages, as the path does for load_mesh.
// The fuzz targets (fuzz/) and their regression tests read meshes through here.
TriangleMesh parse_mesh(const std::string& bytes, const std::filesystem::path& name,
                        const MeshLoadOptions& options = {});

// Maps each triangle's material name to an index into `materials` (by
// Material::name). Triangles of material_names[0] ("") and triangles whose name is
// not a scene material get object_material; each unknown name adds one line to
// `warnings`, so a mesh exported with "Material.001" still loads.
std::vector<std::uint32_t> resolve_materials(const TriangleMesh& mesh,
                                             const std::vector<Material>& materials,
                                             std::uint32_t object_material,
                                             std::vector<std::string>& warnings);

} // namespace wp
