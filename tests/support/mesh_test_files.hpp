// Helpers for the mesh loader tests: files written on the fly into a per-run
// temporary folder (for error cases and binary PLY, which are clearer as bytes in
// the test than as files), a little-endian/big-endian byte writer independent of
// the reader, and geometric references (area, enclosed volume).
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "scene/mesh.hpp"

namespace mesh_test {

inline std::filesystem::path data_dir() {
    return std::filesystem::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "meshes";
}

// A folder for this test process, removed again when the process ends.
class TempDir {
  public:
    TempDir()
        : path_(std::filesystem::temp_directory_path() /
                ("wavepath-mesh-tests-" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec; // best effort: never throw from a destructor
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

inline const std::filesystem::path& temp_dir() {
    static const TempDir dir;
    return dir.path();
}

// Writes `bytes` to a file called `name` in the temporary folder; returns its path.
inline std::filesystem::path write_file(const std::string& name, const std::string& bytes) {
    const auto path = temp_dir() / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// The message load_mesh throws, or "<no error>".
inline std::string error_of(const std::filesystem::path& path,
                            const wp::MeshLoadOptions& options = {}) {
    try {
        (void)wp::load_mesh(path, options);
    } catch (const wp::MeshError& e) {
        return e.what();
    }
    return "<no error>";
}

// Appends values in a chosen byte order, byte by byte (no memcpy of the host's
// representation), so that the reader's byte swapping is checked independently.
class Bytes {
  public:
    explicit Bytes(bool big_endian) : big_(big_endian) {}
    template <class T> Bytes& put(T value) {
        std::uint64_t bits = 0;
        if constexpr (sizeof(T) == 8)
            bits = std::bit_cast<std::uint64_t>(value);
        else if constexpr (sizeof(T) == 4)
            bits = std::bit_cast<std::uint32_t>(value);
        else if constexpr (sizeof(T) == 2)
            bits = std::bit_cast<std::uint16_t>(value);
        else
            bits = std::bit_cast<std::uint8_t>(value);
        for (std::size_t i = 0; i < sizeof(T); ++i) {
            const std::size_t shift = 8 * (big_ ? sizeof(T) - 1 - i : i);
            s_.push_back(static_cast<char>((bits >> shift) & 0xff));
        }
        return *this;
    }
    const std::string& str() const { return s_; }

  private:
    bool big_;
    std::string s_;
};

inline double surface_area(const wp::TriangleMesh& m) {
    double a = 0.0;
    for (const auto& t : m.triangles)
        a += 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]],
                                          m.positions[t[2]] - m.positions[t[0]]));
    return a;
}

// Volume enclosed by a closed mesh by the divergence theorem: positive when the
// front faces point outwards.
inline double signed_volume(const wp::TriangleMesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles)
        v += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
    return v;
}

inline glm::dvec3 face_normal(const wp::TriangleMesh& m, std::size_t i) {
    const auto& t = m.triangles[i];
    return glm::normalize(
        glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
}

} // namespace mesh_test
