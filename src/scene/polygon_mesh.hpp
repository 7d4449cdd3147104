// What the file readers produce and what load_mesh() finishes: indexed polygons
// as the file has them, every index already checked against the positions.
// Internal to src/scene; users see TriangleMesh (mesh.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace wp {

struct PolygonMesh {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals; // empty, or one per position (any non-zero length)
    std::vector<glm::dvec2> uvs;     // empty, or one per position: texture coordinates
    // Polygon p has the corners indices[offsets[p] .. offsets[p + 1]), at least three,
    // in the file's winding. offsets starts with 0.
    std::vector<std::uint32_t> indices;
    std::vector<std::size_t> offsets{0};
    std::vector<std::uint32_t> polygon_materials; // per polygon, into material_names
    std::vector<std::string> material_names{""};
    std::vector<std::string> warnings;

    std::size_t polygon_count() const { return offsets.size() - 1; }
    std::span<const std::uint32_t> polygon(std::size_t p) const {
        return std::span<const std::uint32_t>(indices).subspan(offsets[p],
                                                               offsets[p + 1] - offsets[p]);
    }
    void add_polygon(std::span<const std::uint32_t> corners, std::uint32_t material) {
        indices.insert(indices.end(), corners.begin(), corners.end());
        offsets.push_back(indices.size());
        polygon_materials.push_back(material);
    }
};

// The readers, chosen by load_mesh() by the file's extension. `text` is the whole file; `file`
// names it in messages. Both throw MeshError. read_obj splits vertices by normal only when
// keep_normals is set (an OBJ corner pairs a position with a normal of its own),
// and by texture coordinate only when keep_uvs is.
PolygonMesh read_obj(const std::filesystem::path& file, const std::string& text, bool keep_normals,
                     bool keep_uvs = true);
PolygonMesh read_ply(const std::filesystem::path& file, const std::string& bytes);
// Mitsuba's .serialized (serialized_reader.cpp): the mesh at shape_index.
PolygonMesh read_serialized(const std::filesystem::path& file, const std::string& bytes,
                            std::uint32_t shape_index);

} // namespace wp
