// Mitsuba's own mesh format, `.serialized` (format id 0x041C, versions 3
// and 4), as Mitsuba 3's serialized shape reads it; written here from the
// format's description in Mitsuba's documentation. A file is one or more
// meshes, each a 4-byte header (id, version; little-endian as everything
// else) followed by a zlib stream holding:
//   uint32 flags  0x0001 vertex normals, 0x0002 texture coordinates,
//                 0x0008 vertex colours, 0x0010 "face normals",
//                 0x2000 double precision (otherwise single)
//   name          (version 4 only) a NUL-terminated UTF-8 string
//   uint64 vertex count, uint64 triangle count
//   positions, [normals], [texture coordinates], [colours]: float or double
//   triangles: uint32 x 3 each
// and the file ends with a dictionary: each mesh's byte offset (uint64 in
// version 4, uint32 in version 3) and then the mesh count (uint32). As in
// Mitsuba, mesh 0 is read from the start of the file without the
// dictionary, and another from the offset the dictionary gives.
//
// Mitsuba 3.9.1 reads the 0x0010 flag and does nothing with it (a mesh
// with it and no normals gets smooth normals, measured); wavepath does the
// same. Colours are skipped, as Mitsuba skips them.
//
// Every error names the file and the mesh: "scene.serialized: mesh 1: ...".
#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <zlib.h>

#include "scene/mesh.hpp"
#include "scene/polygon_mesh.hpp"

namespace wp {

namespace {

constexpr std::uint16_t kFormatId = 0x041C;
constexpr std::uint32_t kHasNormals = 0x0001;
constexpr std::uint32_t kHasTexcoords = 0x0002;
constexpr std::uint32_t kHasColors = 0x0008;
constexpr std::uint32_t kDoublePrecision = 0x2000;

// zlib's deflate expands data by at most 1032:1 (its documentation's
// technical details), so a stream of N bytes holds at most about 1032 N:
// counts that need more are corrupt, and refusing them before allocating
// keeps a hostile 100-byte file from asking for terabytes.
constexpr std::uint64_t kMaxInflateRatio = 1032;

// A mesh name longer than this is taken for a missing terminator.
constexpr std::size_t kMaxNameLength = 1 << 16;

std::uint64_t little_endian(const unsigned char* p, int bytes) {
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i)
        v = (v << 8) | p[i];
    return v;
}

// A problem inside one mesh; read_serialized adds the file and the mesh.
struct Problem {
    std::string message;
};

// The bytes of one mesh's zlib stream, inflated as they are asked for.
class Inflater {
  public:
    explicit Inflater(std::string_view input) : input_(input) {
        stream_.next_in = Z_NULL;
        stream_.avail_in = 0;
        if (inflateInit(&stream_) != Z_OK)
            throw Problem{"zlib could not start"};
    }
    ~Inflater() { inflateEnd(&stream_); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    void read(unsigned char* out, std::size_t n) {
        while (n > 0) {
            if (ended_)
                throw Problem{"the zlib stream ends before the mesh does (truncated?)"};
            if (stream_.avail_in == 0 && !input_.empty()) {
                // zlib counts in uInt: feed a large file in pieces.
                const std::size_t piece = std::min<std::size_t>(input_.size(), UINT_MAX);
                stream_.next_in =
                    reinterpret_cast<Bytef*>(const_cast<char*>(input_.data())); // zlib's API
                stream_.avail_in = static_cast<uInt>(piece);
                input_.remove_prefix(piece);
            }
            const std::size_t chunk = std::min<std::size_t>(n, UINT_MAX);
            stream_.next_out = out;
            stream_.avail_out = static_cast<uInt>(chunk);
            const int status = inflate(&stream_, Z_NO_FLUSH);
            const std::size_t produced = chunk - stream_.avail_out;
            out += produced;
            n -= produced;
            if (status == Z_STREAM_END) {
                ended_ = true;
            } else if (status == Z_BUF_ERROR || (status == Z_OK && produced == 0 &&
                                                 stream_.avail_in == 0 && input_.empty())) {
                throw Problem{"file ends early inside its zlib stream (truncated?)"};
            } else if (status != Z_OK) {
                throw Problem{std::string("bad zlib stream (") +
                              (stream_.msg != nullptr ? stream_.msg : zError(status)) + ")"};
            }
        }
    }

    template <typename T> T read_uint() {
        unsigned char b[sizeof(T)];
        read(b, sizeof(T));
        return static_cast<T>(little_endian(b, sizeof(T)));
    }

  private:
    std::string_view input_;
    z_stream stream_{};
    bool ended_ = false;
};

// count x dim numbers of the mesh's precision, as doubles.
std::vector<double> read_numbers(Inflater& in, std::uint64_t count, int dim, bool dbl) {
    const std::size_t size = dbl ? 8 : 4;
    const std::size_t n = static_cast<std::size_t>(count) * static_cast<std::size_t>(dim);
    std::vector<unsigned char> raw(n * size);
    in.read(raw.data(), raw.size());
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned char* p = raw.data() + i * size;
        out[i] = dbl ? std::bit_cast<double>(little_endian(p, 8))
                     : static_cast<double>(
                           std::bit_cast<float>(static_cast<std::uint32_t>(little_endian(p, 4))));
    }
    return out;
}

std::string element_text(std::string_view what, std::size_t index) {
    return std::string(what) + " " + std::to_string(index);
}

// The mesh in `stream` (its zlib stream and whatever follows it).
PolygonMesh read_mesh(std::string_view stream, bool version4) {
    Inflater in(stream);
    const auto flags = in.read_uint<std::uint32_t>();
    const bool dbl = (flags & kDoublePrecision) != 0;
    if (version4) {
        std::string name;
        for (;;) {
            unsigned char c = 0;
            in.read(&c, 1);
            if (c == 0)
                break;
            if (name.size() == kMaxNameLength)
                throw Problem{"the mesh's name has no end within 65536 bytes"};
            name.push_back(static_cast<char>(c));
        }
    }
    const auto vertices = in.read_uint<std::uint64_t>();
    const auto triangles = in.read_uint<std::uint64_t>();
    if (vertices == 0 || triangles == 0)
        throw Problem{"mesh has no faces (" + std::to_string(vertices) + " vertices, " +
                      std::to_string(triangles) + " triangles)"};
    // Mitsuba writes 64-bit indices past 2^32 - 1 vertices; wavepath's are 32-bit.
    if (vertices > std::numeric_limits<std::uint32_t>::max())
        throw Problem{std::to_string(vertices) +
                      " vertices: more than wavepath's 32-bit indices reach"};
    const std::uint64_t bound = kMaxInflateRatio * stream.size() + 64;
    const std::uint64_t per_vertex =
        (3 + ((flags & kHasNormals) ? 3 : 0) + ((flags & kHasTexcoords) ? 2 : 0) +
         ((flags & kHasColors) ? 3 : 0)) *
        (dbl ? 8u : 4u);
    if (triangles > bound / 12 || vertices > bound / per_vertex ||
        vertices * per_vertex + triangles * 12 > bound)
        throw Problem{std::to_string(vertices) + " vertices and " + std::to_string(triangles) +
                      " triangles cannot fit in a " + std::to_string(stream.size()) +
                      "-byte zlib stream (corrupt counts?)"};

    PolygonMesh mesh;
    const std::vector<double> p = read_numbers(in, vertices, 3, dbl);
    mesh.positions.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) {
        mesh.positions[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
        if (!std::isfinite(p[3 * i]) || !std::isfinite(p[3 * i + 1]) ||
            !std::isfinite(p[3 * i + 2]))
            throw Problem{element_text("vertex", i) + ": coordinate is not finite"};
    }
    if (flags & kHasNormals) {
        const std::vector<double> n = read_numbers(in, vertices, 3, dbl);
        mesh.normals.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) {
            const glm::dvec3 v{n[3 * i], n[3 * i + 1], n[3 * i + 2]};
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
                throw Problem{element_text("vertex", i) + ": normal is not finite"};
            if (v == glm::dvec3(0.0))
                throw Problem{element_text("vertex", i) + ": normal has zero length"};
            mesh.normals[i] = v;
        }
    }
    if (flags & kHasTexcoords) {
        const std::vector<double> t = read_numbers(in, vertices, 2, dbl);
        mesh.uvs.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) {
            if (!std::isfinite(t[2 * i]) || !std::isfinite(t[2 * i + 1]))
                throw Problem{element_text("vertex", i) + ": texture coordinate is not finite"};
            mesh.uvs[i] = {t[2 * i], t[2 * i + 1]};
        }
    }
    if (flags & kHasColors)
        read_numbers(in, vertices, 3, dbl); // read past: wavepath has no vertex colours

    std::vector<unsigned char> raw(static_cast<std::size_t>(triangles) * 12);
    in.read(raw.data(), raw.size());
    mesh.indices.reserve(raw.size() / 4);
    mesh.offsets.reserve(triangles + 1);
    mesh.polygon_materials.reserve(triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
        std::uint32_t corners[3];
        for (int k = 0; k < 3; ++k) {
            corners[k] = static_cast<std::uint32_t>(little_endian(raw.data() + 12 * t + 4 * k, 4));
            if (corners[k] >= vertices)
                throw Problem{element_text("triangle", t) + ": vertex index " +
                              std::to_string(corners[k]) + " out of range (" +
                              std::to_string(vertices) + " vertices)"};
        }
        mesh.add_polygon(corners, 0);
    }
    return mesh;
}

} // namespace

PolygonMesh read_serialized(const std::filesystem::path& file, const std::string& bytes,
                            std::uint32_t shape_index) {
    const std::string mesh_name = "mesh " + std::to_string(shape_index);
    auto fail = [&](const std::string& message) -> MeshError {
        return MeshError::in_file(file, message);
    };
    auto header = [&](std::size_t at) {
        if (bytes.size() < at + 4)
            throw fail("file ends early: no room for a serialized mesh header (truncated?)");
        const auto* b = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
        const auto id = little_endian(b, 2);
        const auto version = little_endian(b + 2, 2);
        if (id != kFormatId) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(id));
            throw fail((at == 0 ? std::string() : mesh_name + ": ") +
                       "not a Mitsuba serialized mesh (format id " + hex + ", expected 0x041C)");
        }
        if (version != 3 && version != 4)
            throw fail((at == 0 ? std::string() : mesh_name + ": ") + "serialized format version " +
                       std::to_string(version) +
                       " is not supported (wavepath reads versions 3 and 4)");
        return version == 4;
    };
    const bool version4 = header(0);

    std::size_t offset = 0;
    if (shape_index > 0) {
        // The dictionary at the end: offsets, then the count.
        const std::size_t entry = version4 ? 8 : 4;
        if (bytes.size() < 8)
            throw fail("file ends early: no end-of-file dictionary (truncated?)");
        const auto* end = reinterpret_cast<const unsigned char*>(bytes.data()) + bytes.size();
        const std::uint64_t count = little_endian(end - 4, 4);
        if (count > (bytes.size() - 8) / entry)
            throw fail("the end-of-file dictionary's " + std::to_string(count) +
                       " meshes do not fit in the file (truncated, or not a dictionary?)");
        if (shape_index >= count)
            throw fail("shape_index " + std::to_string(shape_index) +
                       " is out of range: the file holds " + std::to_string(count) +
                       (count == 1 ? " mesh" : " meshes") +
                       (count == 0 ? "" : " (0 to " + std::to_string(count - 1) + ")"));
        const std::size_t dictionary = bytes.size() - 4 - count * entry;
        const std::uint64_t at =
            little_endian(end - 4 - (count - shape_index) * entry, static_cast<int>(entry));
        if (at >= dictionary)
            throw fail(mesh_name + ": its offset " + std::to_string(at) +
                       " lies past the meshes (the dictionary starts at " +
                       std::to_string(dictionary) + ")");
        offset = static_cast<std::size_t>(at);
        if (header(offset) != version4)
            throw fail(mesh_name + ": its version differs from the file's first mesh");
    }
    try {
        return read_mesh(std::string_view(bytes).substr(offset + 4), version4);
    } catch (const Problem& problem) {
        throw MeshError::in_file(file, mesh_name + ": " + problem.message);
    } catch (const std::bad_alloc&) {
        throw MeshError::in_file(file, mesh_name + ": not enough memory for the mesh");
    }
}

} // namespace wp
