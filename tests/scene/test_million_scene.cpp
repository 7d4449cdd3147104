// scenes/million.json and tools/make_displaced_sphere.py: the generated PLY
// is not in the repository, so this test writes it (with the scene file
// beside it) into the build tree and reuses it while the tool is unchanged.
// Skipped with a warning where python3 is missing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/mesh.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = WAVEPATH_SOURCE_DIR;

// The tool's defaults, as its documentation states them.
constexpr std::size_t kResolution = 289;
constexpr double kAmplitude = 0.15;

// <build>/generated/million/: million.json and models/displaced-sphere.ply,
// laid out as in scenes/, so that the scene's relative path is the one tested.
fs::path generated_scene() {
    const fs::path folder = fs::path(WAVEPATH_EXE).parent_path() / "generated" / "million";
    const fs::path ply = folder / "models" / "displaced-sphere.ply";
    const fs::path tool = kSource / "tools" / "make_displaced_sphere.py";
    fs::create_directories(folder / "models");
    fs::copy_file(kSource / "scenes" / "million.json", folder / "million.json",
                  fs::copy_options::overwrite_existing);
    if (!fs::exists(ply) || fs::last_write_time(ply) < fs::last_write_time(tool)) {
        const std::string command = "python3 '" + tool.string() + "' '" + ply.string() + "'";
        if (std::system(command.c_str()) != 0)
            return {};
    }
    return folder / "million.json";
}

// Runs the tool quietly; true when it succeeded.
bool make_sphere(const fs::path& ply, const std::string& arguments) {
    const std::string command = "python3 '" +
                                (kSource / "tools" / "make_displaced_sphere.py").string() + "' '" +
                                ply.string() + "' " + arguments + " >/dev/null";
    return std::system(command.c_str()) == 0;
}

bool have_python() {
    if (std::system("python3 -c 'import sys' >/dev/null 2>&1") == 0)
        return true;
    WARN("skipped: python3 is not available to run tools/make_displaced_sphere.py");
    return false;
}

} // namespace

TEST_CASE("scenes: the million-triangle scene loads its generated displaced sphere",
          "[scene][scenes][million]") {
    if (!have_python())
        return;
    const fs::path scene_file = generated_scene();
    REQUIRE_FALSE(scene_file.empty());

    const auto start = std::chrono::steady_clock::now();
    const wp::Scene s = wp::load_scene(scene_file);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WARN("load_scene(million.json): "
         << s.triangles.size() << " triangles in " << seconds << " s, PLY "
         << fs::file_size(scene_file.parent_path() / "models" / "displaced-sphere.ply")
         << " bytes");

    // Each of the cube's 6 faces is an N x N grid of quads, two triangles each;
    // the room of cornell-box.json has 18 more.
    const std::size_t sphere = 12 * kResolution * kResolution;
    CHECK(sphere >= 1000000);
    REQUIRE(s.triangles.size() == 18 + sphere);
    CHECK(s.warnings.empty()); // no degenerate triangles dropped
    // The sphere (radius 150 +- 22.5 around (278, 175, 280)) inside the room.
    for (std::size_t t = 18; t < s.triangles.size(); ++t)
        for (const glm::dvec3& p : s.triangles[t].v) {
            const double r = glm::length(p - glm::dvec3(278, 175, 280));
            if (r < 150 * (1 - kAmplitude) - 1e-3 || r > 150 * (1 + kAmplitude) + 1e-3 ||
                p.y <= 0.0) {
                FAIL_CHECK("vertex at radius " << r << ", height " << p.y);
                break;
            }
        }
}

TEST_CASE("scenes: the generated sphere is closed, faces outwards and keeps its bumps in range",
          "[scene][scenes][million]") {
    if (!have_python())
        return;
    // A small one from the same code: resolution 8 (768 triangles).
    const wp::test::TempDir dir;
    const fs::path ply = dir / "small.ply";
    REQUIRE(make_sphere(ply, "--resolution 8 --seed 3"));
    const wp::TriangleMesh m = wp::load_mesh(ply);
    CHECK(m.triangles.size() == 12 * 8 * 8);
    CHECK(m.positions.size() == 6 * 8 * 8 + 2); // shared along the cube's edges
    CHECK(m.dropped_degenerate == 0);

    // Closed: every edge is used once in each direction (two triangles meet
    // there, wound consistently).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& t : m.triangles)
        for (std::size_t k = 0; k < 3; ++k)
            edges.emplace_back(t[k], t[(k + 1) % 3]);
    std::sort(edges.begin(), edges.end());
    CHECK(std::adjacent_find(edges.begin(), edges.end()) == edges.end()); // no edge twice one way
    for (const auto& [a, b] : edges)
        CHECK(std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a)));

    // Outwards, with every vertex within the amplitude of the unit sphere:
    // the enclosed volume (divergence theorem) lies between those spheres'.
    double volume = 0.0;
    for (const auto& t : m.triangles)
        volume +=
            glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
    const double ball = 4.0 / 3.0 * 3.14159265358979323846;
    CHECK(volume > ball * std::pow(1 - kAmplitude, 3));
    CHECK(volume < ball * std::pow(1 + kAmplitude, 3));
    for (const glm::dvec3& p : m.positions) {
        CHECK(glm::length(p) >= 1 - kAmplitude - 1e-6);
        CHECK(glm::length(p) <= 1 + kAmplitude + 1e-6);
    }

    // Deterministic: the same arguments give the same bytes; another seed
    // other bumps.
    const fs::path again = dir / "again.ply", other = dir / "other.ply";
    REQUIRE(make_sphere(again, "--resolution 8 --seed 3"));
    REQUIRE(make_sphere(other, "--resolution 8 --seed 4"));
    CHECK(wp::test::read_bytes(ply) == wp::test::read_bytes(again));
    CHECK(wp::load_mesh(other).positions != m.positions);
}
