// Every way a mesh-file shape can be wrong gives one SceneError line: the
// scene file, the JSON pointer of the field, and the problem (for the mesh
// file's own problems, the mesh loader's message naming the mesh file).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/load.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kCamera =
    R"({"eye": [-5, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})";
const std::string kMaterials = R"({"white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]}})";

struct Case {
    const char* what;
    std::string shape;    // the one shape of the scene
    std::string expected; // the whole message after "<dir>/scene.json: "
};

} // namespace

TEST_CASE("loader: every mesh-file error is one line naming the scene, the field and the problem",
          "[scene][load][mesh][errors]") {
    const wp::test::TempDir dir;
    const std::string d = dir.path().string();
    wp::test::write_text(dir / "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    wp::test::write_text(dir / "bad-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n");
    wp::test::write_text(dir / "empty.ply",
                         "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n");
    wp::test::write_text(dir / "model.stl", "solid nothing\n");
    fs::create_directories(dir / "folder.obj");

    const std::string file = R"("type": "mesh", "material": "white", "file": "triangle.obj")";
    auto with = [&](const std::string& transform) {
        return "{" + file + R"(, "transform": )" + transform + "}";
    };
    const std::vector<Case> cases{
        {"missing file", R"({"type": "mesh", "material": "white", "file": "missing.obj"})",
         "/shapes/0/file: " + d + "/missing.obj: cannot open mesh file: No such file or directory"},
        {"a directory", R"({"type": "mesh", "material": "white", "file": "folder.obj"})",
         "/shapes/0/file: " + d + "/folder.obj: cannot open mesh file: it is a directory"},
        {"unknown format", R"({"type": "mesh", "material": "white", "file": "model.stl"})",
         "/shapes/0/file: " + d +
             "/model.stl: unknown mesh format '.stl' (expected .obj, .ply or .serialized)"},
        {"mesh error with a line",
         R"({"type": "mesh", "material": "white", "file": "bad-index.obj"})",
         "/shapes/0/file: " + d +
             "/bad-index.obj:5: face vertex index 9 out of range (3 vertices)"},
        {"mesh error without a line",
         R"({"type": "mesh", "material": "white", "file": "empty.ply"})",
         "/shapes/0/file: " + d + "/empty.ply: mesh has no faces"},
        {"transform beyond the scene limit", with(R"([{"scale": 1e31}])"),
         "/shapes/0/file: " + d +
             "/triangle.obj: vertex 1: coordinate 1e+31 exceeds the scene limit 1e30"},
        {"file not a string", R"({"type": "mesh", "material": "white", "file": 3})",
         "/shapes/0/file: expected a string, got 3"},
        {"empty file name", R"({"type": "mesh", "material": "white", "file": ""})",
         "/shapes/0/file: must name a mesh file (.obj or .ply)"},
        {"file and vertices",
         "{" + file + R"(, "vertices": [[0, 0, 0]], "triangles": [[0, 0, 0]]})",
         "/shapes/0/vertices: give either 'file' or 'vertices' and 'triangles', not both"},
        {"file and triangles", "{" + file + R"(, "triangles": [[0, 1, 2]]})",
         "/shapes/0/triangles: give either 'file' or 'vertices' and 'triangles', not both"},
        {"triangles without vertices (an inline mesh)",
         R"({"type": "mesh", "material": "white", "triangles": [[0, 1, 2]]})",
         "/shapes/0/vertices: missing required field 'vertices'"},
        {"neither file nor vertices", R"({"type": "mesh", "material": "white"})",
         "/shapes/0/file: missing required field 'file' (or give 'vertices' and 'triangles')"},
        {"transform on an inline mesh",
         R"({"type": "mesh", "material": "white", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]], "transform": []})",
         "/shapes/0/transform: 'transform' applies to mesh files only (give 'file'); inline "
         "vertices are already in scene coordinates"},
        {"unknown key", "{" + file + R"(, "smooth": true})",
         "/shapes/0/smooth: unknown key 'smooth' (allowed here: type, file, material, name, "
         "normals, "
         "transform)"},
        {"unknown normals", "{" + file + R"(, "normals": "flat"})",
         "/shapes/0/normals: unknown normals 'flat' (expected file, smooth or none)"},
        {"normals not a string", "{" + file + R"(, "normals": false})",
         "/shapes/0/normals: expected a string, got false"},
        {"unknown material", R"({"type": "mesh", "material": "gold", "file": "triangle.obj"})",
         "/shapes/0/material: unknown material 'gold' (defined: white)"},
        {"transform not an array", with(R"({"scale": 2})"),
         "/shapes/0/transform: expected an array of transform steps, got an object"},
        {"step not an object", with(R"([{"scale": 2}, [1, 2, 3]])"),
         "/shapes/0/transform/1: expected a transform step: an object with one key (translate, "
         "rotate, scale, look_at or matrix), got an array of 3 elements"},
        {"step with two keys", with(R"([{"scale": 2, "translate": [1, 2, 3]}])"),
         "/shapes/0/transform/0: a transform step has exactly one key (translate, rotate, scale, "
         "look_at or matrix), got 2"},
        {"empty step", with(R"([{}])"),
         "/shapes/0/transform/0: a transform step has exactly one key (translate, rotate, scale, "
         "look_at or matrix), got 0"},
        {"unknown step", with(R"([{"spin": 90}])"),
         "/shapes/0/transform/0/spin: unknown transform step 'spin' (expected translate, rotate, "
         "scale, look_at or matrix)"},
        {"translate of 2 numbers", with(R"([{"translate": [1, 2]}])"),
         "/shapes/0/transform/0/translate: expected an array of 3 numbers, got an array of 2 "
         "elements"},
        {"translate with a string", with(R"([{"translate": [1, "2", 3]}])"),
         "/shapes/0/transform/0/translate/1: expected a number, got \"2\""},
        {"rotate without angle", with(R"([{"rotate": {"axis": [0, 0, 1]}}])"),
         "/shapes/0/transform/0/rotate/angle: missing required field 'angle'"},
        {"rotate with an unknown key",
         with(R"([{"rotate": {"angle": 9, "axis": [0, 0, 1], "deg": 9}}])"),
         "/shapes/0/transform/0/rotate/deg: unknown key 'deg' (allowed here: angle, axis)"},
        {"rotate about a zero axis",
         with(R"([{"scale": 2}, {"rotate": {"angle": 90, "axis": [0, 0, 0]}}])"),
         "/shapes/0/transform/1: rotate: axis has zero length"},
        {"rotate as a number", with(R"([{"rotate": 90}])"),
         "/shapes/0/transform/0/rotate: expected an object {\"angle\": degrees, \"axis\": [x, y, "
         "z]}, got 90"},
        {"zero scale", with(R"([{"scale": 0}])"),
         "/shapes/0/transform/0: scale: factor must be non-zero"},
        {"zero scale on one axis", with(R"([{"scale": [1, 0, 1]}])"),
         "/shapes/0/transform/0: scale: factor must be non-zero"},
        {"scale as a string", with(R"([{"scale": "2"}])"),
         "/shapes/0/transform/0/scale: expected a number or an array of 3 numbers, got \"2\""},
        {"look_at without up", with(R"([{"look_at": {"from": [0, 0, 0], "to": [0, 0, 1]}}])"),
         "/shapes/0/transform/0/look_at/up: missing required field 'up'"},
        {"look_at to == from",
         with(R"([{"look_at": {"from": [1, 1, 1], "to": [1, 1, 1], "up": [0, 1, 0]}}])"),
         "/shapes/0/transform/0: look_at: 'to' equals 'from'"},
        {"look_at up parallel",
         with(R"([{"look_at": {"from": [0, 0, 0], "to": [0, 2, 0], "up": [0, 1, 0]}}])"),
         "/shapes/0/transform/0: look_at: 'up' is zero or parallel to the direction 'to' - 'from'"},
        {"matrix of 3 rows", with(R"([{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}])"),
         "/shapes/0/transform/0/matrix: expected 4 rows of 4 numbers, got an array of 3 elements"},
        {"matrix row of 3",
         with(R"([{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1], [0, 0, 0, 1]]}])"),
         "/shapes/0/transform/0/matrix/2: expected a row of 4 numbers, got an array of 3 elements"},
        {"matrix entry not a number",
         with(R"([{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, null], [0, 0, 0, 1]]}])"),
         "/shapes/0/transform/0/matrix/2/3: expected a number, got null"},
        {"projective matrix",
         with(R"([{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}])"),
         "/shapes/0/transform/0: matrix: last row must be 0 0 0 1 (only affine transforms)"},
        {"singular matrix",
         with(R"([{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [1, 1, 0, 0], [0, 0, 0, 1]]}])"),
         "/shapes/0/transform/0: matrix: transform is singular (it flattens the object, so normals "
         "cannot be transformed)"},
    };
    const std::string scene = (dir / "scene.json").string();
    for (const Case& c : cases) {
        INFO(c.what);
        wp::test::write_text(dir / "scene.json", R"({"camera": )" + kCamera + R"(, "materials": )" +
                                                     kMaterials + R"(, "shapes": [)" + c.shape +
                                                     "]}");
        std::string message = "<no error>";
        try {
            (void)wp::load_scene(dir / "scene.json");
        } catch (const wp::SceneError& e) {
            message = e.what();
        }
        CHECK(message == scene + ": " + c.expected);
        CHECK(std::count(message.begin(), message.end(), '\n') == 0);
    }
}

TEST_CASE("loader: the mesh-file error table's base scene loads", "[scene][load][mesh][errors]") {
    // So that every case above fails for its own reason, not the scene's.
    const wp::test::TempDir dir;
    wp::test::write_text(dir / "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    wp::test::write_text(
        dir / "scene.json",
        R"({"camera": )" + kCamera + R"(, "materials": )" + kMaterials +
            R"(, "shapes": [{"type": "mesh", "material": "white", "file": "triangle.obj", "normals": "smooth", "transform": [{"scale": 2}]}]})");
    const wp::Scene s = wp::load_scene(dir / "scene.json");
    REQUIRE(s.triangles.size() == 1);
    CHECK(s.triangles[0].v[1] == glm::dvec3(2, 0, 0));
}
