// The .serialized reader (scene/serialized_reader.cpp): files written here
// byte by byte (mesh_test::Bytes, compressed by zlib's compress2), which
// must come back as the arrays they were written from, exactly; the
// committed tests/data/meshes/two-meshes.serialized against the values
// Mitsuba 3.9.1 reads from it; and hostile files, each one line naming the
// file, with every truncation of a valid file refused cleanly.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <zlib.h>

#include "scene/mesh.hpp"
#include "support/mesh_test_files.hpp"

using mesh_test::Bytes;
using mesh_test::data_dir;
using mesh_test::error_of;
using mesh_test::write_file;

namespace {

struct SourceMesh {
    std::string name = "mesh";
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals; // unit length, or empty
    std::vector<glm::dvec2> uvs;
    std::vector<glm::dvec3> colors;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    bool double_precision = false;
};

template <class Vec> void put_all(Bytes& b, const std::vector<Vec>& values, bool dbl) {
    for (const Vec& v : values)
        for (int k = 0; k < Vec::length(); ++k)
            dbl ? (void)b.put(v[k]) : (void)b.put(static_cast<float>(v[k]));
}

// One mesh's uncompressed stream, as the format describes it.
std::string payload(const SourceMesh& m, int version) {
    Bytes b(false);
    std::uint32_t flags = m.double_precision ? 0x2000u : 0x1000u;
    if (!m.normals.empty())
        flags |= 0x0001;
    if (!m.uvs.empty())
        flags |= 0x0002;
    if (!m.colors.empty())
        flags |= 0x0008;
    b.put(flags);
    if (version == 4) {
        for (char c : m.name)
            b.put(c);
        b.put('\0');
    }
    b.put(static_cast<std::uint64_t>(m.positions.size()));
    b.put(static_cast<std::uint64_t>(m.triangles.size()));
    put_all(b, m.positions, m.double_precision);
    put_all(b, m.normals, m.double_precision);
    put_all(b, m.uvs, m.double_precision);
    put_all(b, m.colors, m.double_precision);
    for (const auto& t : m.triangles)
        for (std::uint32_t i : t)
            b.put(i);
    return b.str();
}

std::string deflate(const std::string& raw) {
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::string out(size, '\0');
    REQUIRE(compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                      reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                      Z_BEST_COMPRESSION) == Z_OK);
    out.resize(size);
    return out;
}

std::string header(int version, std::uint16_t id = 0x041C) {
    Bytes b(false);
    b.put(id).put(static_cast<std::uint16_t>(version));
    return b.str();
}

// A whole file: each mesh's header and stream, then the dictionary.
std::string serialized_file(const std::vector<SourceMesh>& meshes, int version = 4) {
    std::string out;
    std::vector<std::uint64_t> offsets;
    for (const SourceMesh& m : meshes) {
        offsets.push_back(out.size());
        out += header(version) + deflate(payload(m, version));
    }
    Bytes dictionary(false);
    for (std::uint64_t o : offsets)
        version == 4 ? (void)dictionary.put(o)
                     : (void)dictionary.put(static_cast<std::uint32_t>(o));
    dictionary.put(static_cast<std::uint32_t>(meshes.size()));
    return out + dictionary.str();
}

// A bumpy grid of n x n vertices with irregular coordinates (none of them
// exact in float), unit normals and texture coordinates.
SourceMesh grid(int n, double seed, bool dbl) {
    SourceMesh m;
    m.double_precision = dbl;
    std::mt19937_64 rng(static_cast<std::uint64_t>(seed * 1000));
    std::uniform_real_distribution<double> jitter(-0.1, 0.1);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.positions.push_back({i + jitter(rng) + seed, j + jitter(rng), jitter(rng)});
            m.normals.push_back(glm::normalize(glm::dvec3(jitter(rng), jitter(rng), 1.0)));
            m.uvs.push_back({(i + jitter(rng)) / n, (j + jitter(rng)) / n});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const auto a = static_cast<std::uint32_t>(j * n + i);
            const auto w = static_cast<std::uint32_t>(n);
            m.triangles.push_back({a, a + 1, a + w + 1});
            m.triangles.push_back({a, a + w + 1, a + w});
        }
    return m;
}

// What the reader must give for `value` written at the mesh's precision.
double stored(double value, bool dbl) {
    return dbl ? value : static_cast<double>(static_cast<float>(value));
}

void check_same(const wp::TriangleMesh& got, const SourceMesh& want) {
    const bool dbl = want.double_precision;
    REQUIRE(got.positions.size() == want.positions.size());
    REQUIRE(got.triangles == want.triangles);
    REQUIRE(got.normals.size() == want.normals.size());
    REQUIRE(got.uvs.size() == want.uvs.size());
    for (std::size_t i = 0; i < want.positions.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            CHECK(got.positions[i][k] == stored(want.positions[i][k], dbl));
            // load_mesh renormalises the file's normals; the written ones are
            // unit length to the precision they were written in.
            if (!want.normals.empty())
                CHECK(std::abs(got.normals[i][k] - stored(want.normals[i][k], dbl)) <
                      (dbl ? 1e-15 : 2e-7));
        }
    for (std::size_t i = 0; i < want.uvs.size(); ++i)
        for (int k = 0; k < 2; ++k)
            CHECK(got.uvs[i][k] == stored(want.uvs[i][k], dbl));
}

wp::MeshLoadOptions index(std::uint32_t shape_index) {
    wp::MeshLoadOptions o;
    o.shape_index = shape_index;
    return o;
}

} // namespace

TEST_CASE("serialized: single and double precision give the written mesh exactly",
          "[scene][mesh][serialized]") {
    for (bool dbl : {false, true}) {
        INFO((dbl ? "double" : "single") << " precision");
        const SourceMesh source = grid(9, 0.25, dbl);
        const auto path =
            write_file(dbl ? "grid-d.serialized" : "grid-s.serialized", serialized_file({source}));
        const wp::TriangleMesh mesh = wp::load_mesh(path);
        check_same(mesh, source);
        CHECK(mesh.faces_read == 128);
        CHECK(mesh.dropped_degenerate == 0);
    }
}

TEST_CASE("serialized: shape_index picks one of several meshes, in versions 3 and 4",
          "[scene][mesh][serialized]") {
    for (int version : {3, 4}) {
        INFO("version " << version);
        // Different sizes and precisions, and colours (read past) on the middle one.
        std::vector<SourceMesh> meshes = {grid(3, 0.0, false), grid(5, 10.0, true),
                                          grid(4, 20.0, false)};
        meshes[1].colors.assign(meshes[1].positions.size(), glm::dvec3(0.25, 0.5, 1.0));
        meshes[2].normals.clear();
        const auto path = write_file("three-v" + std::to_string(version) + ".serialized",
                                     serialized_file(meshes, version));
        for (std::uint32_t i = 0; i < 3; ++i) {
            INFO("shape_index " << i);
            check_same(wp::load_mesh(path, index(i)), meshes[i]);
        }
        CHECK(error_of(path, index(3)) ==
              path.string() + ": shape_index 3 is out of range: the file holds 3 meshes (0 to 2)");
    }
}

TEST_CASE("serialized: the committed file reads as Mitsuba 3.9.1 reads it",
          "[scene][mesh][serialized]") {
    // Mitsuba 3.9.1 (scalar_rgb), load_dict({'type': 'serialized', 'filename':
    // 'two-meshes.serialized', 'shape_index': i}): vertex_positions_buffer,
    // vertex_normals_buffer, vertex_texcoords_buffer and faces_buffer.
    const auto path = data_dir() / "two-meshes.serialized";
    const wp::TriangleMesh first = wp::load_mesh(path, index(0));
    const std::vector<glm::dvec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5}};
    const std::vector<glm::dvec3> normals = {{0, 0, 1},
                                             {0, 0.6000000238418579, 0.800000011920929},
                                             {0, 0, 1},
                                             {0.6000000238418579, 0, 0.800000011920929}};
    const std::vector<glm::dvec2> uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    const std::vector<std::array<std::uint32_t, 3>> faces = {{0, 1, 2}, {1, 3, 2}};
    CHECK(first.positions == positions);
    CHECK(first.uvs == uvs);
    CHECK(first.triangles == faces);
    REQUIRE(first.normals.size() == 4);
    for (std::size_t i = 0; i < 4; ++i)
        CHECK(glm::length(first.normals[i] - normals[i]) < 1e-7);

    // Mesh 1: double precision, colours and the face-normals flag, which
    // Mitsuba 3.9.1 ignores (it computes smooth normals: the file has none).
    const wp::TriangleMesh second = wp::load_mesh(path, index(1));
    std::vector<glm::dvec3> moved = positions;
    for (glm::dvec3& p : moved)
        p.x += 2.0;
    CHECK(second.positions == moved);
    CHECK(second.triangles == faces);
    CHECK(second.normals.empty());
    CHECK(second.uvs.empty());
}

TEST_CASE("serialized: hostile files are one line naming the file",
          "[scene][mesh][serialized][errors]") {
    const SourceMesh good = grid(3, 0.0, false);
    const std::string valid = serialized_file({good, grid(2, 5.0, true)});
    auto error = [](const std::string& name, const std::string& bytes,
                    std::uint32_t shape_index = 0) {
        const auto path = write_file(name, bytes);
        const std::string message = error_of(path, index(shape_index));
        CHECK(message.find('\n') == std::string::npos);
        const std::string prefix = path.string() + ": ";
        REQUIRE(message.rfind(prefix, 0) == 0);
        return message.substr(prefix.size());
    };

    CHECK(error("empty.serialized", "") ==
          "file ends early: no room for a serialized mesh header (truncated?)");
    CHECK(error("id.serialized", header(4, 0x1C04) + valid.substr(4)) ==
          "not a Mitsuba serialized mesh (format id 0x1C04, expected 0x041C)");
    CHECK(error("version.serialized", header(5) + valid.substr(4)) ==
          "serialized format version 5 is not supported (wavepath reads versions 3 and 4)");
    CHECK(error("zlib.serialized", header(4) + "this is not a zlib stream") ==
          "mesh 0: bad zlib stream (incorrect header check)");
    CHECK(error("short.serialized", valid.substr(0, 30)) ==
          "mesh 0: file ends early inside its zlib stream (truncated?)");
    CHECK(error("index.serialized", valid, 2) ==
          "shape_index 2 is out of range: the file holds 2 meshes (0 to 1)");
    // A dictionary that claims more meshes than the file has room for.
    std::string many = valid;
    many[many.size() - 4] = '\xff';
    many[many.size() - 3] = '\xff';
    CHECK(error("many.serialized", many, 1) ==
          "the end-of-file dictionary's 65535 meshes do not fit in the file (truncated, or not "
          "a dictionary?)");
    // Mesh 1's offset pointed past the meshes.
    std::string far = valid;
    far[far.size() - 5] = '\x7f'; // the top byte of mesh 1's offset
    CHECK(error("far.serialized", far, 1).rfind("mesh 1: its offset ", 0) == 0);

    // Counts no stream of this size can hold (2^40 vertices: past 32-bit indices).
    SourceMesh absurd = good;
    std::string raw = payload(absurd, 4);
    const std::size_t counts = 4 + absurd.name.size() + 1;
    Bytes huge(false);
    huge.put(std::uint64_t{1} << 40).put(std::uint64_t{2});
    raw.replace(counts, 16, huge.str());
    CHECK(error("vertices.serialized", header(4) + deflate(raw)) ==
          "mesh 0: 1099511627776 vertices: more than wavepath's 32-bit indices reach");
    raw = payload(absurd, 4);
    Bytes lots(false);
    lots.put(std::uint64_t{9}).put(std::uint64_t{1} << 50);
    raw.replace(counts, 16, lots.str());
    const std::string stream = deflate(raw);
    CHECK(error("triangles.serialized", header(4) + stream) ==
          "mesh 0: 9 vertices and 1125899906842624 triangles cannot fit in a " +
              std::to_string(stream.size()) + "-byte zlib stream (corrupt counts?)");

    SourceMesh nan = good;
    nan.positions[4].y = std::numeric_limits<double>::quiet_NaN();
    CHECK(error("nan.serialized", serialized_file({nan})) ==
          "mesh 0: vertex 4: coordinate is not finite");
    SourceMesh inf_normal = good;
    inf_normal.normals[2].x = std::numeric_limits<double>::infinity();
    CHECK(error("normal.serialized", serialized_file({inf_normal})) ==
          "mesh 0: vertex 2: normal is not finite");
    SourceMesh bad_index = good;
    bad_index.triangles[5][1] = 9;
    CHECK(error("bad-index.serialized", serialized_file({bad_index})) ==
          "mesh 0: triangle 5: vertex index 9 out of range (9 vertices)");
    SourceMesh empty = good;
    empty.triangles.clear();
    CHECK(error("no-faces.serialized", serialized_file({empty})) ==
          "mesh 0: mesh has no faces (9 vertices, 0 triangles)");
}

TEST_CASE("serialized: every truncation of a valid file is a clean error",
          "[scene][mesh][serialized][errors]") {
    const std::string valid = serialized_file({grid(3, 0.0, false), grid(3, 5.0, true)});
    int refused = 0;
    for (std::size_t cut = 0; cut < valid.size(); ++cut) {
        for (std::uint32_t shape_index : {0u, 1u}) {
            const auto path = write_file("cut.serialized", valid.substr(0, cut));
            const std::string message = error_of(path, index(shape_index));
            // Mesh 0 needs nothing after its own stream; cuts past it still read.
            if (message == "<no error>") {
                CHECK(shape_index == 0);
                continue;
            }
            ++refused;
            CHECK(message.find('\n') == std::string::npos);
            CHECK(message.rfind(path.string() + ": ", 0) == 0);
        }
    }
    CHECK(refused > static_cast<int>(valid.size()));
}
