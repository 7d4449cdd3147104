// Mesh files' triangles are held indexed in the scene (scene/triangle_list.hpp)
// and must be, bit for bit, the triangles the loaders used to store whole:
// for a JSON and a Mitsuba scene, with and without normals and texture
// coordinates, per-face materials, a mirroring transform, flip_normals and
// flip_tex_coords, each triangle is compared with one built the old way from
// load_mesh's mesh, and the flattened device arrays (triangles, normals,
// texture coordinates, lights, hierarchy) with those of the same scene whose
// triangles are all held whole.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "render/device_scene.hpp"
#include "scene/load.hpp"
#include "scene/mesh.hpp"
#include "scene/mesh_normals.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using wp::Triangle;

std::string data_file(const std::string& name) {
    return (fs::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "meshes" / name).string();
}

// An OBJ file with texture coordinates at every corner and two materials
// (cube.obj has them at one face's corners only, which the reader drops).
std::string write_textured_obj(const fs::path& dir) {
    const fs::path path = dir / "textured.obj";
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n"
                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.25\n"
                           "f 1/1 2/2 3/3 4/4\nusemtl red\nf 1/1 2/2 5/5\nf 2/2 3/3 5/5\n";
    return path.string();
}

bool same(const Triangle& a, const Triangle& b) {
    return a.v == b.v && a.material == b.material && a.has_normals == b.has_normals &&
           a.normals == b.normals && a.has_uvs == b.has_uvs && a.uvs == b.uvs;
}

// The mesh's triangles as the JSON loader stored them whole before.
void add_json_mesh_whole(const wp::Scene& scene, const std::string& file,
                         const wp::MeshLoadOptions& options, std::uint32_t material,
                         std::vector<Triangle>& out) {
    const wp::TriangleMesh mesh = wp::load_mesh(file, options);
    std::vector<std::string> warnings;
    const std::vector<std::uint32_t> materials =
        wp::resolve_materials(mesh, scene.materials, material, warnings);
    const auto& at = mesh.positions;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& [a, b, c] = mesh.triangles[t];
        Triangle triangle{{at[a], at[b], at[c]}, materials[t]};
        if (!mesh.normals.empty()) {
            triangle.has_normals = true;
            triangle.normals = {mesh.normals[a], mesh.normals[b], mesh.normals[c]};
        }
        if (!mesh.uvs.empty()) {
            triangle.has_uvs = true;
            triangle.uvs = {mesh.uvs[a], mesh.uvs[b], mesh.uvs[c]};
        }
        out.push_back(triangle);
    }
}

// The mesh's triangles as the Mitsuba loader stored them whole before.
void add_mitsuba_mesh_whole(const std::string& file, const wp::Transform& to_world, bool flip,
                            bool flip_tex_coords, std::uint32_t material,
                            std::vector<Triangle>& out) {
    wp::MeshLoadOptions options;
    options.transform = to_world;
    options.texture_coordinates = true;
    wp::TriangleMesh mesh = wp::load_mesh(file, options);
    if (!mesh.has_normals())
        mesh.normals = wp::smooth_vertex_normals(mesh.positions, mesh.triangles);
    const bool reverse = flip != to_world.flips_orientation();
    for (const auto& [a, b, c] : mesh.triangles) {
        Triangle t{{mesh.positions[a], mesh.positions[b], mesh.positions[c]}, material};
        t.has_normals = true;
        t.normals = {mesh.normals[a], mesh.normals[b], mesh.normals[c]};
        if (!mesh.uvs.empty()) {
            t.has_uvs = true;
            t.uvs = {mesh.uvs[a], mesh.uvs[b], mesh.uvs[c]};
            if (file.ends_with(".obj") && !flip_tex_coords)
                for (glm::dvec2& uv : t.uvs)
                    uv.y = 1.0 - uv.y;
        }
        if (reverse) {
            std::swap(t.v[1], t.v[2]);
            std::swap(t.normals[1], t.normals[2]);
            std::swap(t.uvs[1], t.uvs[2]);
        }
        if (flip)
            for (glm::dvec3& n : t.normals)
                n = -n;
        out.push_back(t);
    }
}

template <typename T, typename Allocator>
bool same_bytes(const std::vector<T, Allocator>& a, const std::vector<T, Allocator>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// `scene` as loaded, and with `whole` in place of its triangles: the same
// triangles, the same flattened arrays.
void check_against_whole(const wp::Scene& scene, const std::vector<Triangle>& whole) {
    REQUIRE(scene.triangles.size() == whole.size());
    for (std::size_t i = 0; i < whole.size(); ++i) {
        INFO("triangle " << i);
        CHECK(same(scene.triangles[i], whole[i]));
    }
    wp::Scene reference = scene;
    reference.triangles.clear();
    for (const Triangle& t : whole)
        reference.triangles.push_back(t);
    for (const bool hierarchy : {false, true}) {
        INFO("hierarchy " << hierarchy);
        const wp::DeviceScene got = wp::flatten_scene(scene, hierarchy);
        const wp::DeviceScene want = wp::flatten_scene(reference, hierarchy);
        CHECK(same_bytes(got.triangles, want.triangles));
        CHECK(same_bytes(got.triangle_normals, want.triangle_normals));
        CHECK(same_bytes(got.triangle_uvs, want.triangle_uvs));
        CHECK(same_bytes(got.lights, want.lights));
        CHECK(same_bytes(got.bvh_nodes, want.bvh_nodes));
        CHECK(got.bvh_nodes.empty() != hierarchy);
    }
}

std::uint32_t material_named(const wp::Scene& scene, const std::string& name) {
    for (std::uint32_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == name)
            return i;
    FAIL("no material " << name);
    return 0;
}

} // namespace

TEST_CASE("indexed meshes: a JSON scene's mesh files give the triangles stored whole before") {
    wp::test::TempDir dir;
    const fs::path path = dir / "scene.json";
    const std::string textured = write_textured_obj(dir.path());
    std::ofstream(path) << R"({
        "camera": {"eye": [-5, 0.5, 0.5], "look_at": [0, 0.5, 0.5], "up": [0, 0, 1], "fov": 60,
                   "resolution": [8, 8]},
        "materials": {
            "white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
            "red": {"type": "diffuse", "reflectance": {"type": "checkerboard"}},
            "light": {"type": "emitter", "radiance": [10, 10, 10]}},
        "shapes": [
            {"type": "quad", "vertices": [[0, 0, 3], [1, 0, 3], [1, 1, 3], [0, 1, 3]], "material": "light"},
            {"type": "mesh", "file": ")" +
                               data_file("cube.obj") + R"(", "material": "white"},
            {"type": "triangle", "vertices": [[0, 0, 5], [1, 0, 5], [0, 1, 5]], "material": "light"},
            {"type": "mesh", "file": ")" +
                               data_file("crease.obj") + R"(", "material": "white"},
            {"type": "mesh", "file": ")" +
                               data_file("cube_ascii.ply") +
                               R"(", "material": "red", "normals": "smooth",
             "transform": [{"scale": 2}, {"translate": [3, 0, 0]}]},
            {"type": "mesh", "file": ")" +
                               data_file("strips.ply") +
                               R"(", "material": "white", "normals": "none"},
            {"type": "mesh", "file": ")" +
                               textured + R"(", "material": "white"}]})";
    const wp::Scene scene = wp::load_scene(path);

    std::vector<Triangle> whole;
    for (std::size_t i = 0; i < 2; ++i) // the quad
        whole.push_back(scene.triangles[i]);
    wp::MeshLoadOptions options;
    options.texture_coordinates = true; // the scene has a texture
    add_json_mesh_whole(scene, data_file("cube.obj"), options, material_named(scene, "white"),
                        whole);
    whole.push_back(scene.triangles[whole.size()]); // the inline triangle
    add_json_mesh_whole(scene, data_file("crease.obj"), options, material_named(scene, "white"),
                        whole);
    wp::MeshLoadOptions placed = options;
    placed.normals = wp::NormalSource::Smooth;
    placed.transform = wp::Transform::compose(std::vector<wp::Transform>{
        wp::Transform::scale(2.0), wp::Transform::translate({3.0, 0.0, 0.0})});
    add_json_mesh_whole(scene, data_file("cube_ascii.ply"), placed, material_named(scene, "red"),
                        whole);
    wp::MeshLoadOptions flat = options;
    flat.normals = wp::NormalSource::None;
    add_json_mesh_whole(scene, data_file("strips.ply"), flat, material_named(scene, "white"),
                        whole);
    add_json_mesh_whole(scene, textured, options, material_named(scene, "white"), whole);

    // What the comparison covers: per-face materials, normals and texture
    // coordinates where the files have them, and triangles without either.
    std::size_t with_normals = 0, with_uvs = 0, red = 0;
    for (const Triangle& t : whole) {
        with_normals += t.has_normals;
        with_uvs += t.has_uvs;
        red += t.material == material_named(scene, "red");
    }
    CHECK(with_normals > 0);
    CHECK(with_normals < whole.size());
    CHECK(with_uvs > 2);
    CHECK(red > 4);
    check_against_whole(scene, whole);
}

TEST_CASE("indexed meshes: a Mitsuba scene's mesh files give the triangles stored whole before") {
    wp::test::TempDir dir;
    const fs::path path = dir / "scene.xml";
    const std::string textured = write_textured_obj(dir.path());
    auto shape = [](const std::string& type, const std::string& file, const std::string& extra) {
        return "<shape type=\"" + type + "\"><string name=\"filename\" value=\"" + file + "\"/>" +
               extra +
               "<bsdf type=\"diffuse\"><texture type=\"checkerboard\" name=\"reflectance\"/>"
               "</bsdf></shape>\n";
    };
    std::ofstream(path)
        << "<scene version=\"3.0.0\">\n"
           "<sensor type=\"perspective\"><float name=\"fov\" value=\"60\"/>"
           "<transform name=\"to_world\"><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" "
           "up=\"0, 1, 0\"/></transform><film type=\"hdrfilm\"><integer name=\"width\" "
           "value=\"8\"/><integer name=\"height\" value=\"8\"/></film></sensor>\n"
           "<shape type=\"rectangle\"><transform name=\"to_world\"><translate z=\"3\"/>"
           "</transform><emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter>"
           "</shape>\n" +
               shape("obj", textured,
                     "<boolean name=\"flip_normals\" value=\"true\"/>"
                     "<boolean name=\"flip_tex_coords\" value=\"false\"/>"
                     "<transform name=\"to_world\"><scale x=\"-1\"/></transform>") +
               shape("obj", data_file("crease.obj"), "") +
               shape("ply", data_file("cube_ascii.ply"),
                     "<boolean name=\"flip_normals\" value=\"true\"/>") +
               "</scene>\n";
    const wp::Scene scene = wp::load_scene(path);

    std::vector<Triangle> whole{scene.triangles[0], scene.triangles[1]}; // the rectangle
    const std::uint32_t first = scene.triangles[2].material;
    add_mitsuba_mesh_whole(textured, wp::Transform::scale({-1.0, 1.0, 1.0}), true, false, first,
                           whole);
    const std::uint32_t second = scene.triangles[whole.size()].material;
    add_mitsuba_mesh_whole(data_file("crease.obj"), wp::Transform(), false, true, second, whole);
    const std::uint32_t third = scene.triangles[whole.size()].material;
    add_mitsuba_mesh_whole(data_file("cube_ascii.ply"), wp::Transform(), true, true, third, whole);
    CHECK(whole[2].has_uvs);
    CHECK(whole[2].uvs[0] != whole[2].uvs[1]);
    CHECK(first != second);
    CHECK(second != third);
    check_against_whole(scene, whole);
}
