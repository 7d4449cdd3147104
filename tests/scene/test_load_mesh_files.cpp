// Mesh shapes that name a file: the loader reads OBJ and PLY files relative to
// the scene file, places them with the transform list, maps usemtl names to
// scene materials and forwards the mesh's warnings. Positions are checked
// against points computed by hand from the files' corners.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kCamera =
    R"({"eye": [-5, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})";
const std::string kMaterials = R"({
    "white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
    "red": {"type": "diffuse", "reflectance": [0.7, 0.1, 0.1]},
    "light": {"type": "emitter", "radiance": [10, 10, 10]}})";

fs::path data_file(const std::string& name) {
    return fs::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "meshes" / name;
}

// A scene folder with copies of the test meshes in models/, so that the
// scene's relative paths are resolved against the scene file, not the
// working directory.
struct SceneFolder {
    wp::test::TempDir dir;
    SceneFolder() {
        fs::create_directories(dir / "models");
        for (const char* name : {"cube.obj", "cube_ascii.ply", "crease.obj", "strips.ply"})
            fs::copy_file(data_file(name), dir / "models" / name);
    }
    wp::Scene load(const std::string& shapes) const {
        const fs::path path = dir / "scene.json";
        wp::test::write_text(path, R"({"camera": )" + kCamera + R"(, "materials": )" + kMaterials +
                                       R"(, "shapes": )" + shapes + "}");
        return wp::load_scene(path);
    }
};

// The mesh shape of `file` with `extra` keys (each starting with a comma).
std::string mesh(const std::string& file, const std::string& extra = "") {
    return R"([{"type": "mesh", "file": ")" + file + R"(", "material": "white")" + extra + "}]";
}

// The distinct corner positions of the triangles, sorted: the geometry,
// independent of how each file's polygons were split.
std::vector<glm::dvec3> corners(const wp::Scene& s) {
    std::vector<glm::dvec3> out;
    for (const wp::Triangle& t : s.triangles)
        out.insert(out.end(), t.v.begin(), t.v.end());
    std::sort(out.begin(), out.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Volume enclosed by the scene's triangles (divergence theorem): positive when
// every front face points outwards.
double signed_volume(const wp::Scene& s) {
    double v = 0.0;
    for (const wp::Triangle& t : s.triangles)
        v += glm::dot(t.v[0], glm::cross(t.v[1], t.v[2])) / 6.0;
    return v;
}

// Every corner of the unit cube [0, 1]^3, as the two test files list them.
const std::array<glm::dvec3, 8> kCubeCorners{
    glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(1, 1, 0), glm::dvec3(0, 1, 0),
    glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 1), glm::dvec3(1, 1, 1), glm::dvec3(0, 1, 1)};

// True when p is within 1e-12 of f(c) for some cube corner c.
template <class F> bool is_image_of_a_corner(const glm::dvec3& p, F f) {
    return std::any_of(kCubeCorners.begin(), kCubeCorners.end(),
                       [&](const glm::dvec3& c) { return glm::length(p - f(c)) <= 1e-12; });
}

} // namespace

TEST_CASE("loader: an OBJ and a PLY mesh file become scene triangles", "[scene][load][mesh]") {
    const SceneFolder folder;
    const wp::Scene s = folder.load(R"([
        {"type": "mesh", "file": "models/cube.obj", "material": "white"},
        {"type": "mesh", "file": "models/cube_ascii.ply", "material": "red"},
        {"type": "triangle", "vertices": [[0, 0, 5], [1, 0, 5], [0, 1, 5]], "material": "white"}])");
    // Six quads each, two triangles per quad; then the inline triangle, in file order.
    REQUIRE(s.triangles.size() == 12 + 12 + 1);
    CHECK(s.triangles.back().v[0] == glm::dvec3(0, 0, 5));
    // Without a transform, both files give exactly the cube's eight corners.
    wp::Scene obj = s, ply = s;
    obj.triangles.clear();
    ply.triangles.clear();
    for (std::size_t i = 0; i < 12; ++i) {
        obj.triangles.push_back(s.triangles[i]);
        ply.triangles.push_back(s.triangles[12 + i]);
    }
    CHECK(corners(obj).size() == 8);
    CHECK(corners(obj) == corners(ply));
    for (const glm::dvec3& p : corners(obj))
        CHECK(is_image_of_a_corner(p, [](const glm::dvec3& c) { return c; }));
    // Both cubes face outwards: the enclosed volume is +1.
    CHECK(signed_volume(obj) == Approx(1.0).epsilon(1e-12));
    CHECK(signed_volume(ply) == Approx(1.0).epsilon(1e-12));
    for (std::size_t t = 12; t < 24; ++t)
        CHECK(s.triangles[t].material == 1); // PLY faces: the object's material, "red"
}

TEST_CASE("loader: usemtl names map to scene materials, others to the object's material",
          "[scene][load][mesh]") {
    const SceneFolder folder;
    // cube.obj: two faces before any usemtl, two 'red', one 'blue' (no such
    // scene material), one 'red'.
    const wp::Scene s = folder.load(mesh("models/cube.obj"));
    REQUIRE(s.triangles.size() == 12);
    const std::array<std::uint32_t, 12> expected{0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 1, 1};
    for (std::size_t t = 0; t < 12; ++t) {
        INFO("triangle " << t);
        CHECK(s.triangles[t].material == expected[t]);
    }
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0] == "/shapes/0/file: " + (folder.dir / "models" / "cube.obj").string() +
                               ": usemtl 'blue' is not a scene material; its faces get the "
                               "object's material");
}

TEST_CASE("loader: mesh transform steps place the vertices", "[scene][load][mesh]") {
    const SceneFolder folder;
    using F = glm::dvec3 (*)(const glm::dvec3&);
    struct Case {
        const char* transform;
        F expected; // the transform applied by hand to a corner
    };
    const std::vector<Case> cases{
        {R"([{"translate": [1, -2, 3]}])",
         [](const glm::dvec3& c) { return c + glm::dvec3(1, -2, 3); }},
        // Scale 2, then a quarter turn about +z ((x, y) -> (-y, x)), then move.
        {R"([{"scale": 2}, {"rotate": {"angle": 90, "axis": [0, 0, 5]}}, {"translate": [10, 0, 0]}])",
         [](const glm::dvec3& c) { return glm::dvec3(10 - 2 * c.y, 2 * c.x, 2 * c.z); }},
        // The same steps in the other order act differently: list order is
        // application order.
        {R"([{"translate": [10, 0, 0]}, {"rotate": {"angle": 90, "axis": [0, 0, 1]}}, {"scale": 2}])",
         [](const glm::dvec3& c) { return glm::dvec3(-2 * c.y, 2 * (c.x + 10), 2 * c.z); }},
        {R"([{"scale": [1, 2, 3]}])",
         [](const glm::dvec3& c) { return glm::dvec3(c.x, 2 * c.y, 3 * c.z); }},
        // Rows as on paper: the same quarter turn and the offset in the last column.
        {R"([{"matrix": [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]]}])",
         [](const glm::dvec3& c) { return glm::dvec3(5 - c.y, 6 + c.x, 7 + c.z); }},
        // Local +z towards 'to', +y up: here the object's axes stay, and it moves to 'from'.
        {R"([{"look_at": {"from": [1, 2, 3], "to": [1, 2, 9], "up": [0, 4, 0]}}])",
         [](const glm::dvec3& c) { return c + glm::dvec3(1, 2, 3); }},
        // Local +z towards world +x and local +y up (+z), so local +x is
        // y x z = (0, 0, 1) x (1, 0, 0) = (0, 1, 0).
        {R"([{"look_at": {"from": [0, 0, 0], "to": [3, 0, 0], "up": [0, 0, 1]}}])",
         [](const glm::dvec3& c) { return glm::dvec3(c.z, c.x, c.y); }},
        // A mirror: the winding is reversed too, so the cube still faces outwards.
        {R"([{"scale": [-1, 1, 1]}])",
         [](const glm::dvec3& c) { return glm::dvec3(-c.x, c.y, c.z); }},
    };
    for (const char* file : {"models/cube.obj", "models/cube_ascii.ply"}) {
        for (const Case& c : cases) {
            INFO(file << " transform " << c.transform);
            const wp::Scene s =
                folder.load(mesh(file, std::string(R"(, "transform": )") + c.transform));
            REQUIRE(s.triangles.size() == 12);
            CHECK(corners(s).size() == 8);
            for (const glm::dvec3& p : corners(s))
                CHECK(is_image_of_a_corner(p, c.expected));
            // Volume of the image of the unit cube: |det| of the linear part,
            // by hand from the expected map's images of the unit axes.
            const glm::dvec3 o = c.expected(glm::dvec3(0));
            const double det = glm::dot(c.expected(glm::dvec3(1, 0, 0)) - o,
                                        glm::cross(c.expected(glm::dvec3(0, 1, 0)) - o,
                                                   c.expected(glm::dvec3(0, 0, 1)) - o));
            CHECK(signed_volume(s) == Approx(std::abs(det)).epsilon(1e-12));
        }
    }
}

TEST_CASE("loader: the first OBJ face lands where its corners are sent", "[scene][load][mesh]") {
    const SceneFolder folder;
    // cube.obj's first face is "f 1 4 3 2", corners (0,0,0) (0,1,0) (1,1,0) (1,0,0),
    // a convex quad split as a fan: (1 4 3), (1 3 2).
    const wp::Scene s = folder.load(mesh(
        "models/cube.obj",
        R"(, "transform": [{"scale": 2}, {"rotate": {"angle": 90, "axis": [0, 0, 1]}}, {"translate": [10, 0, 0]}])"));
    REQUIRE(s.triangles.size() == 12);
    const std::array<glm::dvec3, 3> first{glm::dvec3(10, 0, 0), glm::dvec3(8, 0, 0),
                                          glm::dvec3(8, 2, 0)};
    for (std::size_t k = 0; k < 3; ++k) {
        INFO("corner " << k);
        CHECK(glm::length(s.triangles[0].v[k] - first[k]) <= 1e-12);
    }
}

TEST_CASE("loader: the normals option gives the triangles their shading normals: the file's, "
          "smooth ones, or none",
          "[scene][load][mesh]") {
    const SceneFolder folder;
    // crease.obj: two triangles in the plane z = 0 (front faces +z), the file
    // normals (0, 0, 2) on the first and (0, 0.6, 0.8) on the second.
    const wp::Scene plain = folder.load(mesh("models/crease.obj"));
    REQUIRE(plain.triangles.size() == 2);
    for (const char* normals : {"file", "smooth", "none"}) {
        INFO(normals);
        const wp::Scene s = folder.load(
            mesh("models/crease.obj", std::string(R"(, "normals": ")") + normals + "\""));
        REQUIRE(s.triangles.size() == plain.triangles.size());
        for (std::size_t t = 0; t < s.triangles.size(); ++t)
            CHECK(s.triangles[t].v == plain.triangles[t].v);
        CHECK(s.warnings.empty());
        const std::string option = normals;
        for (const wp::Triangle& t : s.triangles) {
            CHECK(t.has_normals == (option != "none"));
            if (!t.has_normals)
                continue;
            const glm::dvec3 expected = option == "smooth" || t.v[2] == glm::dvec3(1, 1, 0)
                                            ? glm::dvec3(0, 0, 1)
                                            : glm::dvec3(0, 0.6, 0.8);
            for (const glm::dvec3& n : t.normals)
                CHECK(glm::length(n - expected) < 1e-12);
        }
    }
    // The default is the file's.
    CHECK(plain.triangles[0].has_normals);
}

TEST_CASE("loader: dropped degenerate triangles are counted in the scene's warnings",
          "[scene][load][mesh]") {
    const SceneFolder folder;
    // strips.ply: four good strip triangles and one that repeats a vertex.
    const wp::Scene s = folder.load(mesh("models/strips.ply"));
    CHECK(s.triangles.size() == 4);
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0] == "/shapes/0/file: " + (folder.dir / "models" / "strips.ply").string() +
                               ": dropped 1 degenerate (zero-area) triangles");
}

TEST_CASE("loader: mesh files are found relative to the scene file", "[scene][load][mesh]") {
    const SceneFolder folder;
    fs::create_directories(folder.dir / "scenes");
    const fs::path scene = folder.dir / "scenes" / "up.json";
    wp::test::write_text(scene, R"({"camera": )" + kCamera + R"(, "materials": )" + kMaterials +
                                    R"(, "shapes": )" + mesh("../models/cube.obj") + "}");
    // From a working directory where no "../models" exists.
    const fs::path before = fs::current_path();
    fs::current_path(folder.dir / "models");
    wp::Scene s;
    CHECK_NOTHROW(s = wp::load_scene(scene));
    fs::current_path(before);
    CHECK(s.triangles.size() == 12);
    // An absolute path is taken as it is.
    CHECK(folder.load(mesh((folder.dir / "models" / "cube.obj").string())).triangles.size() == 12);
}

TEST_CASE("loader: an emissive material on a mesh file makes emitting triangles",
          "[scene][load][mesh]") {
    const SceneFolder folder;
    const wp::Scene s = folder.load(R"([{"type": "mesh", "file": "models/cube_ascii.ply",
                                          "material": "light"}])");
    REQUIRE(s.triangles.size() == 12);
    for (const wp::Triangle& t : s.triangles)
        CHECK(s.materials[t.material].is_emissive());
}
