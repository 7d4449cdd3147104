// Wavefront OBJ through Debian's tinyobjloader (2.0.0rc10), behind a check of
// our own. tinyobjloader parses the numbers, but on its own it would let bad
// files through: it reports index 0 without naming the problem well, only warns
// about indices past the end, turns a negative index that reaches before the
// first vertex into a negative array index, skips faces with fewer than three
// corners, reads "nan" and "inf" as 0, and stores a face's corner count in an
// unsigned char (so a face with 256+ corners would corrupt the index stream).
// So one pass over the text first checks every `v`, `vn` and `f` line and gives
// the one-line "file:line: message" errors; it also records each face's corner
// count and `usemtl` name, which tinyobjloader drops when there is no .mtl file.
// Only then does tinyobjloader read the file, and its output is walked with the
// counts from the check. .mtl files are not read: `usemtl` names are matched
// against scene materials later (resolve_materials in mesh.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <istream>
#include <streambuf>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <tiny_obj_loader.h>

#include "scene/mesh.hpp"
#include "scene/parse_number.hpp"
#include "scene/polygon_mesh.hpp"
#include "util/one_line.hpp"

namespace wp {

namespace {

std::string_view trim(std::string_view s) {
    const auto begin = s.find_first_not_of(" \t");
    if (begin == std::string_view::npos)
        return {};
    const auto end = s.find_last_not_of(" \t");
    return s.substr(begin, end - begin + 1);
}

// The three kinds of thing an OBJ face corner can refer to.
enum Kind { Position = 0, Texcoord = 1, Normal = 2 };
constexpr const char* kind_name[] = {"vertex", "texture", "normal"};
constexpr const char* kind_plural[] = {"vertices", "texture coordinates", "normals"};

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// The check pass described at the top of the file.
class ObjCheck {
  public:
    ObjCheck(const std::filesystem::path& file, const std::string& text)
        : file_(file), text_(text) {}

    void run() {
        std::size_t line_number = 0;
        std::size_t pos = 0;
        // A UTF-8 byte-order mark (Windows editors write one) would make the
        // first line's keyword unknown: that line would be dropped, and the
        // faces indexing it reported out of range. Both passes skip it.
        if (text_.compare(0, kByteOrderMark.size(), kByteOrderMark) == 0) {
            pos = kByteOrderMark.size();
            copied_ = true;
        }
        while (pos < text_.size()) {
            std::size_t end = text_.find('\n', pos);
            if (end == std::string::npos)
                end = text_.size();
            const std::size_t line_start = pos;
            std::string_view line(text_.data() + pos, end - pos);
            pos = end + 1;
            ++line_number;
            if (!line.empty() && line.back() == '\r')
                line.remove_suffix(1);
            const bool used = check_line(line, line_number);
            const bool inner_return = line.find('\r') != std::string_view::npos;
            if (!copied_ && (!used || inner_return)) {
                copied_ = true;
                copy_.assign(text_, 0, line_start);
            }
            if (copied_) {
                if (used) {
                    const std::size_t at = copy_.size();
                    copy_ += line;
                    std::replace(copy_.begin() + static_cast<std::ptrdiff_t>(at), copy_.end(), '\r',
                                 ' ');
                }
                copy_ += '\n';
            }
        }
        // A positive index may point forwards (tinyobjloader allows it), so those
        // past the count at their line are settled once the totals are known.
        for (const Forward& f : forward_)
            if (f.index > static_cast<std::int64_t>(count[f.kind]))
                fail(f.line, std::string("face ") + kind_name[f.kind] + " index " +
                                 std::to_string(f.index) + " out of range (" +
                                 std::to_string(count[f.kind]) + " " + kind_plural[f.kind] + ")");
    }

    std::size_t count[3] = {0, 0, 0}; // v, vt, vn lines
    std::vector<std::uint32_t> face_sizes;
    std::vector<std::uint32_t> face_materials;
    std::vector<std::string> material_names{""};
    bool every_corner_has_normal = true;
    bool every_corner_has_texcoord = true;

    // What tinyobjloader reads: the file itself, or, when the file has a
    // statement that is not used (see check_line), a carriage return inside
    // a line (tinyobjloader ends a line there, the check does not) or a
    // byte-order mark, a copy with those lines blank, those returns spaces
    // and no mark. So tinyobjloader sees exactly the lines the check saw, and
    // none of the statements whose parsers have undefined behaviour on
    // hostile numbers (a `vw` skin weight's joint id of 1e309 is converted to
    // int: found by obj_fuzzer). Blank lines keep the line numbers.
    const std::string& text_for_tinyobjloader() const { return copied_ ? copy_ : text_; }

  private:
    struct Forward {
        std::size_t line;
        std::int64_t index;
        Kind kind;
    };

    [[noreturn]] void fail(std::size_t line, const std::string& message) const {
        throw MeshError::at_line(file_, line, message);
    }

    // Checks one line; returns whether tinyobjloader is to read it: the
    // statements wavepath uses or that only name things (v, vn, vt, f, usemtl,
    // mtllib, o, g, s), comments and blank lines. Everything else (vw, l, p, t,
    // curves, unknown words) is of no use to a triangle mesh.
    bool check_line(std::string_view line, std::size_t n) {
        std::string_view rest = line;
        const std::string_view keyword = next_token(rest);
        if (keyword == "v") {
            check_vector(rest, n, "vertex");
            ++count[Position];
        } else if (keyword == "vn") {
            const double length2 = check_vector(rest, n, "normal");
            if (length2 == 0.0)
                fail(n, "normal has zero length");
            ++count[Normal];
        } else if (keyword == "vt") {
            check_texcoord(rest, n);
            ++count[Texcoord];
        } else if (keyword == "f") {
            check_face(rest, n);
        } else if (keyword == "usemtl") {
            const std::string name(trim(rest));
            const auto [it, inserted] = material_index_.try_emplace(
                name, static_cast<std::uint32_t>(material_names.size()));
            if (inserted)
                material_names.push_back(name);
            current_material_ = it->second;
        } else if (!(keyword.empty() || keyword.front() == '#' || keyword == "mtllib" ||
                     keyword == "o" || keyword == "g" || keyword == "s")) {
            return false;
        }
        return true;
    }

    // Reads x y z (anything after them, such as a w or a colour, is left to
    // tinyobjloader) and returns the squared length.
    double check_vector(std::string_view rest, std::size_t n, const char* what) const {
        double length2 = 0.0;
        for (int i = 0; i < 3; ++i) {
            const std::string_view token = next_token(rest);
            if (token.empty())
                fail(n, std::string(what) + " needs three coordinates, got " + std::to_string(i));
            double x = 0.0;
            if (!parse_double(token, x))
                fail(n,
                     "cannot read " + std::string(what) + " coordinate '" + excerpt(token) + "'");
            if (!std::isfinite(x))
                fail(n, std::string(what) + " coordinate is not finite ('" + excerpt(token) + "')");
            length2 += x * x;
        }
        return length2;
    }

    // Reads u [v [w]]: v defaults to 0 and w is ignored, as tinyobjloader does.
    void check_texcoord(std::string_view rest, std::size_t n) const {
        for (int i = 0; i < 2; ++i) {
            const std::string_view token = next_token(rest);
            if (token.empty()) {
                if (i == 0)
                    fail(n, "texture coordinate needs at least u");
                return;
            }
            double x = 0.0;
            if (!parse_double(token, x))
                fail(n, "cannot read texture coordinate '" + excerpt(token) + "'");
            if (!std::isfinite(x))
                fail(n, "texture coordinate is not finite ('" + excerpt(token) + "')");
        }
    }

    void check_face(std::string_view rest, std::size_t n) {
        std::uint32_t corners = 0;
        for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
            // v, v/vt, v//vn or v/vt/vn
            std::string_view part[3];
            std::size_t parts = 0;
            std::string_view t = token;
            while (parts < 3) {
                const auto slash = t.find('/');
                part[parts++] = t.substr(0, slash);
                if (slash == std::string_view::npos)
                    break;
                t.remove_prefix(slash + 1);
                if (parts == 3)
                    fail(n, "cannot read face corner '" + excerpt(token) + "'");
            }
            if (part[Position].empty())
                fail(n, "cannot read face corner '" + excerpt(token) + "'");
            for (std::size_t k = 0; k < parts; ++k)
                if (!part[k].empty())
                    check_index(part[k], static_cast<Kind>(k), token, n);
            if (parts < 3 || part[Normal].empty())
                every_corner_has_normal = false;
            if (parts < 2 || part[Texcoord].empty())
                every_corner_has_texcoord = false;
            ++corners;
        }
        if (corners < 3)
            fail(n, "face has " + std::to_string(corners) + " vertices, needs at least 3");
        face_sizes.push_back(corners);
        face_materials.push_back(current_material_);
    }

    void check_index(std::string_view part, Kind kind, std::string_view token, std::size_t n) {
        std::int64_t index = 0;
        if (!parse_integer(part, index))
            fail(n, "cannot read face corner '" + excerpt(token) + "'");
        const std::string what = std::string("face ") + kind_name[kind] + " index ";
        if (index == 0)
            fail(n, what + "0 is invalid (OBJ indices start at 1)");
        const auto so_far = static_cast<std::int64_t>(count[kind]);
        if (index < 0 && -index > so_far)
            fail(n, what + std::to_string(index) + " reaches before the first " + kind_name[kind] +
                        " (" + std::to_string(so_far) + " defined so far)");
        if (index > so_far)
            forward_.push_back({n, index, kind});
    }

    const std::filesystem::path& file_;
    const std::string& text_;
    std::uint32_t current_material_ = 0;
    std::unordered_map<std::string, std::uint32_t> material_index_{{"", 0}};
    std::vector<Forward> forward_;
    bool copied_ = false;
    std::string copy_;
};

// A face corner's position, texture coordinate and normal numbers.
struct VertexKey {
    std::uint32_t position, texcoord, normal;
    bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
    std::size_t operator()(const VertexKey& k) const {
        return std::hash<std::uint64_t>()((std::uint64_t{k.position} << 32) ^
                                          (std::uint64_t{k.texcoord} << 16) ^ k.normal);
    }
};

// Lets tinyobjloader read the text already in memory instead of a second copy.
class MemoryBuffer : public std::streambuf {
  public:
    explicit MemoryBuffer(const std::string& text) {
        char* p = const_cast<char*>(text.data()); // the get area is only read
        setg(p, p, p + text.size());
    }
};

} // namespace

PolygonMesh read_obj(const std::filesystem::path& file, const std::string& text, bool keep_normals,
                     bool keep_uvs) {
    ObjCheck check(file, text);
    check.run();
    if (check.count[Position] > UINT32_MAX)
        throw MeshError::in_file(file, "more than 2^32 - 1 vertices");

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warnings; // all about things the check covers, or about .mtl files
    std::string errors;
    MemoryBuffer buffer(check.text_for_tinyobjloader());
    std::istream in(&buffer);
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &in,
                          /*readMatFn=*/nullptr, /*triangulate=*/false)) {
        const std::string first_line = errors.substr(0, errors.find('\n'));
        throw MeshError::in_file(file, "tinyobjloader: " + first_line);
    }

    // tinyobjloader keeps the faces in file order, split into shapes at each `o`,
    // `g` and `usemtl`; concatenated they are the faces the check saw.
    std::vector<const tinyobj::index_t*> corners;
    std::size_t corner_total = 0;
    for (const std::uint32_t s : check.face_sizes)
        corner_total += s;
    corners.reserve(corner_total);
    for (const tinyobj::shape_t& shape : shapes)
        for (const tinyobj::index_t& idx : shape.mesh.indices)
            corners.push_back(&idx);
    if (corners.size() != corner_total || attrib.vertices.size() != 3 * check.count[Position])
        throw MeshError::in_file(file, "tinyobjloader read " + std::to_string(corners.size()) +
                                           " face corners where the check counted " +
                                           std::to_string(corner_total));

    PolygonMesh mesh;
    mesh.material_names = check.material_names;
    mesh.positions.resize(check.count[Position]);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        mesh.positions[i] = {attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
                             attrib.vertices[3 * i + 2]};

    const bool use_normals = keep_normals && check.every_corner_has_normal && corner_total > 0;
    const bool use_uvs = keep_uvs && check.every_corner_has_texcoord && check.count[Texcoord] > 0 &&
                         corner_total > 0;
    // With normals or texture coordinates, a mesh vertex is a (position,
    // texture coordinate, normal) triple: the same position meets different
    // normals along a crease and different coordinates along a texture seam.
    const bool split = use_normals || use_uvs;
    std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> vertex_of_corner;
    std::vector<glm::dvec3> corner_positions;
    if (split) {
        vertex_of_corner.reserve(mesh.positions.size() * 2);
        corner_positions.reserve(mesh.positions.size());
        if (use_normals)
            mesh.normals.reserve(mesh.positions.size());
        if (use_uvs)
            mesh.uvs.reserve(mesh.positions.size());
    }

    mesh.indices.reserve(corner_total);
    mesh.offsets.reserve(check.face_sizes.size() + 1);
    mesh.polygon_materials.reserve(check.face_sizes.size());
    std::vector<std::uint32_t> polygon;
    std::size_t next = 0;
    for (std::size_t f = 0; f < check.face_sizes.size(); ++f) {
        polygon.clear();
        for (std::uint32_t k = 0; k < check.face_sizes[f]; ++k) {
            const tinyobj::index_t& idx = *corners[next++];
            const auto v = static_cast<std::uint32_t>(idx.vertex_index);
            if (!split) {
                polygon.push_back(v);
                continue;
            }
            const auto vn = use_normals ? static_cast<std::uint32_t>(idx.normal_index) : 0u;
            const auto vt = use_uvs ? static_cast<std::uint32_t>(idx.texcoord_index) : 0u;
            const auto [it, inserted] = vertex_of_corner.try_emplace(
                VertexKey{v, vt, vn}, static_cast<std::uint32_t>(corner_positions.size()));
            if (inserted) {
                corner_positions.push_back(mesh.positions[v]);
                if (use_normals) {
                    const std::size_t n = 3 * std::size_t{vn};
                    mesh.normals.push_back(
                        {attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]});
                }
                if (use_uvs) {
                    const std::size_t t = 2 * std::size_t{vt};
                    mesh.uvs.push_back({attrib.texcoords[t], 1.0 - attrib.texcoords[t + 1]});
                }
            }
            polygon.push_back(it->second);
        }
        mesh.add_polygon(polygon, check.face_materials[f]);
    }
    if (split)
        mesh.positions = std::move(corner_positions);
    if (!use_normals && keep_normals && check.count[Normal] > 0 && corner_total > 0)
        mesh.warnings.push_back(file.string() +
                                ": some face corners have no normal, so the file's normals "
                                "are not used");
    return mesh;
}

} // namespace wp
