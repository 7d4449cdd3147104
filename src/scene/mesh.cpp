#include "scene/mesh.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <unordered_map>
#include <utility>

#include "scene/mesh_normals.hpp"
#include "scene/polygon_mesh.hpp"
#include "scene/polygon_triangulation.hpp"
#include "scene/validate.hpp"
#include "util/file.hpp"
#include "util/one_line.hpp"

namespace wp {

MeshError MeshError::in_file(const std::filesystem::path& file, const std::string& message) {
    return MeshError(file.string() + ": " + message);
}

MeshError MeshError::at_line(const std::filesystem::path& file, std::size_t line,
                             const std::string& message) {
    return MeshError(file.string() + ":" + std::to_string(line) + ": " + message);
}

MeshError MeshError::at_element(const std::filesystem::path& file, const std::string& element,
                                std::size_t index, const std::string& message) {
    return MeshError(file.string() + ": " + excerpt(element) + " " + std::to_string(index) + ": " +
                     message);
}

namespace {

// The file's bytes, or a MeshError in the words of docs/meshes.md.
std::string read_whole_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw MeshError::in_file(path, "cannot open mesh file: it is a directory");
    try {
        return read_file_text(path);
    } catch (const FileError& error) {
        throw MeshError::in_file(path, "cannot open mesh file: " + error.reason());
    }
}

// Throws unless the name has a mesh extension; checked before the file is read.
void check_mesh_extension(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext != ".obj" && ext != ".ply" && ext != ".serialized")
        throw MeshError::in_file(path, ext.empty()
                                           ? "unknown mesh format: the file name has no "
                                             "extension (expected .obj, .ply or .serialized)"
                                           : "unknown mesh format '" + ext +
                                                 "' (expected .obj, .ply or .serialized)");
}

std::string format_number(double x) {
    std::array<char, 32> buf{};
    const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), x).ptr;
    return std::string(buf.data(), end);
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Transforms, triangulates, drops degenerate triangles and sets up normals.
TriangleMesh finish(const std::filesystem::path& file, PolygonMesh&& poly,
                    const MeshLoadOptions& options) {
    if (poly.polygon_count() == 0)
        throw MeshError::in_file(file, "mesh has no faces");

    TriangleMesh mesh;
    mesh.source = file.string();
    mesh.faces_read = poly.polygon_count();
    mesh.material_names = std::move(poly.material_names);
    mesh.warnings = std::move(poly.warnings);
    mesh.positions = std::move(poly.positions);
    if (options.texture_coordinates)
        mesh.uvs = std::move(poly.uvs); // one per position, which triangulation keeps

    // The readers rejected non-finite input; a transform can still overflow, and
    // the scene's float32 limit applies to the placed mesh.
    const Transform& xf = options.transform;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        glm::dvec3& p = mesh.positions[i];
        if (!xf.is_identity())
            p = xf.apply_to_point(p);
        if (!finite(p))
            throw MeshError::at_element(file, "vertex", i,
                                        "coordinate is not finite after the transform");
        const double largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        if (largest > scene_limits::max_coordinate)
            throw MeshError::at_element(file, "vertex", i,
                                        "coordinate " + format_number(largest) +
                                            " exceeds the scene limit 1e30");
    }
    if (options.normals == NormalSource::File && !poly.normals.empty()) {
        mesh.normals = std::move(poly.normals);
        for (glm::dvec3& n : mesh.normals)
            n = xf.apply_to_normal(n); // also normalises the file's normals
    }

    // Triangulating after the transform is the same as before it (affine maps keep
    // convexity and simplicity), and the zero-area test then sees the triangles
    // the scene will hold, as validate_scene() will.
    const bool flip = xf.flips_orientation();
    std::vector<std::array<std::uint32_t, 3>> pieces;
    mesh.triangles.reserve(poly.polygon_count());
    mesh.triangle_materials.reserve(poly.polygon_count());
    for (std::size_t f = 0; f < poly.polygon_count(); ++f) {
        pieces.clear();
        triangulate_polygon(poly.polygon(f), mesh.positions, pieces);
        for (std::array<std::uint32_t, 3> t : pieces) {
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
                is_zero_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]])) {
                ++mesh.dropped_degenerate;
                continue;
            }
            if (flip)
                std::swap(t[1], t[2]);
            mesh.triangles.push_back(t);
            mesh.triangle_materials.push_back(poly.polygon_materials[f]);
        }
    }
    // The polygons are dead once triangulated: freed before the normals.
    std::vector<std::uint32_t>().swap(poly.indices);
    std::vector<std::size_t>().swap(poly.offsets);
    std::vector<std::uint32_t>().swap(poly.polygon_materials);
    if (mesh.triangles.empty())
        throw MeshError::in_file(file, "all " + std::to_string(mesh.dropped_degenerate) +
                                           " triangles are degenerate (zero area)");
    if (mesh.dropped_degenerate > 0)
        mesh.warnings.push_back(file.string() + ": dropped " +
                                std::to_string(mesh.dropped_degenerate) +
                                " degenerate (zero-area) triangles");

    if (options.normals == NormalSource::Smooth)
        mesh.normals = smooth_vertex_normals(mesh.positions, mesh.triangles);
    return mesh;
}

// The file's polygons as its format's reader gives them.
PolygonMesh read_polygons(const std::string& bytes, const std::filesystem::path& name,
                          const MeshLoadOptions& options) {
    check_mesh_extension(name);
    const std::string ext = lower_extension(name);
    return ext == ".obj"   ? read_obj(name, bytes, options.normals == NormalSource::File,
                                      options.texture_coordinates)
           : ext == ".ply" ? read_ply(name, bytes)
                           : read_serialized(name, bytes, options.shape_index);
}

} // namespace

TriangleMesh load_mesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
    check_mesh_extension(path);
    // The file's bytes are freed before finish() triangulates: a big binary
    // PLY is about as large as the triangles it becomes (docs/meshes.md).
    PolygonMesh poly = read_polygons(read_whole_file(path), path, options);
    return finish(path, std::move(poly), options);
}

TriangleMesh parse_mesh(const std::string& bytes, const std::filesystem::path& name,
                        const MeshLoadOptions& options) {
    return finish(name, read_polygons(bytes, name, options), options);
}

std::vector<std::uint32_t> resolve_materials(const TriangleMesh& mesh,
                                             const std::vector<Material>& materials,
                                             std::uint32_t object_material,
                                             std::vector<std::string>& warnings) {
    std::unordered_map<std::string, std::uint32_t> by_name;
    for (std::size_t i = 0; i < materials.size(); ++i)
        by_name.emplace(materials[i].name, static_cast<std::uint32_t>(i));
    std::vector<std::uint32_t> scene_index(mesh.material_names.size(), object_material);
    for (std::size_t m = 1; m < mesh.material_names.size(); ++m) {
        const auto it = by_name.find(mesh.material_names[m]);
        if (it != by_name.end())
            scene_index[m] = it->second;
        else
            warnings.push_back(one_line(mesh.source + ": usemtl '" +
                                        excerpt(mesh.material_names[m]) +
                                        "' is not a scene material; its faces get the object's "
                                        "material"));
    }
    std::vector<std::uint32_t> out(mesh.triangle_materials.size());
    for (std::size_t t = 0; t < out.size(); ++t)
        out[t] = scene_index[mesh.triangle_materials[t]];
    return out;
}

} // namespace wp
