// The Mitsuba 3 export (scene/mitsuba_export.hpp) read back: the XML through
// a real XML parser (expat), the PLY files through wavepath's own mesh reader,
// the camera reconstructed the way Mitsuba builds its rays and compared with
// the camera docs/scene-format.md defines. Rendering the export with Mitsuba
// itself is tests/app/test_cli_export.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <expat.h>
#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/mesh.hpp"
#include "scene/mitsuba_export.hpp"
#include "support/scene_builder.hpp"
#include "support/temp_dir.hpp"
#include "util/file.hpp"

namespace {

namespace fs = std::filesystem;
const std::string kScenes = WAVEPATH_SOURCE_DIR "/scenes/";

// ---- The XML as a tree -------------------------------------------------------

struct Element {
    std::string tag;
    std::map<std::string, std::string> attributes;
    std::vector<Element> children;

    std::string attribute(const std::string& key) const {
        auto it = attributes.find(key);
        return it == attributes.end() ? std::string() : it->second;
    }
    std::vector<const Element*> all(const std::string& child_tag) const {
        std::vector<const Element*> out;
        for (const Element& c : children)
            if (c.tag == child_tag)
                out.push_back(&c);
        return out;
    }
    // The one child with this tag and, if given, this `name` attribute.
    const Element& one(const std::string& child_tag, const std::string& name = "") const {
        const Element* found = nullptr;
        int count = 0;
        for (const Element& c : children)
            if (c.tag == child_tag && (name.empty() || c.attribute("name") == name))
                found = &c, ++count;
        INFO("<" << tag << "> child <" << child_tag << " name=\"" << name << "\">");
        REQUIRE(count == 1);
        return *found;
    }
};

// Parses with expat, which rejects anything that is not well-formed XML.
Element parse_xml(const std::string& text) {
    struct State {
        Element root;
        std::vector<Element*> open;
    } state;
    XML_Parser parser = XML_ParserCreate("UTF-8");
    XML_SetUserData(parser, &state);
    XML_SetElementHandler(
        parser,
        [](void* data, const XML_Char* tag, const XML_Char** attributes) {
            auto& s = *static_cast<State*>(data);
            Element e;
            e.tag = tag;
            for (int i = 0; attributes[i]; i += 2)
                e.attributes[attributes[i]] = attributes[i + 1];
            if (s.open.empty()) {
                s.root = std::move(e);
                s.open.push_back(&s.root);
            } else {
                s.open.back()->children.push_back(std::move(e));
                s.open.push_back(&s.open.back()->children.back());
            }
        },
        [](void* data, const XML_Char*) { static_cast<State*>(data)->open.pop_back(); });
    const bool ok = XML_Parse(parser, text.data(), static_cast<int>(text.size()), 1) != 0;
    const std::string error = ok ? "" : XML_ErrorString(XML_GetErrorCode(parser));
    const auto line = XML_GetCurrentLineNumber(parser);
    XML_ParserFree(parser);
    INFO("XML error at line " << line << ": " << error << "\n" << text);
    REQUIRE(ok);
    return state.root;
}

double parse_number(const std::string& text) {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    REQUIRE(used == text.size());
    return value;
}

glm::dvec3 parse_triple(const std::string& text) {
    std::vector<double> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        values.push_back(parse_number(item.substr(item.find_first_not_of(' '))));
    REQUIRE(values.size() == 3);
    return {values[0], values[1], values[2]};
}

glm::dvec3 rgb_value(const Element& parent, const std::string& name) {
    return parse_triple(parent.one("rgb", name).attribute("value"));
}

// The BSDF with this id, and the shapes by type.
const Element& bsdf_with_id(const Element& scene, const std::string& id) {
    for (const Element* b : scene.all("bsdf"))
        if (b->attribute("id") == id)
            return *b;
    FAIL("no <bsdf id=\"" << id << "\">");
    return scene;
}

std::vector<const Element*> shapes_of_type(const Element& scene, const std::string& type) {
    std::vector<const Element*> out;
    for (const Element* s : scene.all("shape"))
        if (s->attribute("type") == type)
            out.push_back(s);
    return out;
}

// ---- The camera -------------------------------------------------------------

struct CameraVectors {
    glm::dvec3 forward, right, up; // wavepath's: unit forward, right and up scaled to the film
};

// What docs/scene-format.md defines: the view direction, the image's right
// cross(view direction, up), its top towards up, fov the vertical full angle.
CameraVectors scene_format_camera(const wp::Camera& c) {
    const glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
    const glm::dvec3 right_unit = glm::normalize(glm::cross(forward, c.up));
    const glm::dvec3 top_unit = glm::cross(right_unit, forward);
    const double half_height = std::tan(c.vertical_fov_degrees * M_PI / 360.0);
    const double aspect = static_cast<double>(c.width) / c.height;
    return {forward, right_unit * (half_height * aspect), top_unit * half_height};
}

// What Mitsuba's perspective sensor does with the sensor's XML: lookat gives
// the camera-to-world frame (left = normalize(cross(up, dir)), up' =
// cross(dir, left)); the film's x runs along -left and its y along -up' from
// the top left corner, over tan(fov_x / 2) and tan(fov_x / 2) / aspect at
// unit distance (fov_axis "x"; perspective.cpp in Mitsuba 3).
CameraVectors mitsuba_camera_from_xml(const Element& sensor) {
    REQUIRE(sensor.attribute("type") == "perspective");
    REQUIRE(sensor.one("string", "fov_axis").attribute("value") == "x");
    const double fov_x = parse_number(sensor.one("float", "fov").attribute("value"));
    const Element& lookat = sensor.one("transform", "to_world").one("lookat");
    const glm::dvec3 origin = parse_triple(lookat.attribute("origin"));
    const glm::dvec3 target = parse_triple(lookat.attribute("target"));
    const glm::dvec3 up = parse_triple(lookat.attribute("up"));
    const Element& film = sensor.one("film");
    const double width = parse_number(film.one("integer", "width").attribute("value"));
    const double height = parse_number(film.one("integer", "height").attribute("value"));

    const glm::dvec3 dir = glm::normalize(target - origin);
    const glm::dvec3 left = glm::normalize(glm::cross(up, dir));
    const glm::dvec3 new_up = glm::cross(dir, left);
    const double half_width = std::tan(fov_x * M_PI / 360.0);
    return {dir, -left * half_width, new_up * half_width * height / width};
}

void check_close(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    INFO("(" << a.x << ", " << a.y << ", " << a.z << ") against (" << b.x << ", " << b.y << ", "
             << b.z << ")");
    CHECK(glm::length(a - b) <= tolerance * std::max(1.0, glm::length(b)));
}

void check_camera(const wp::Scene& scene) {
    const Element xml = parse_xml(wp::export_mitsuba(scene, "x").xml);
    const Element& sensor = xml.one("sensor");
    const CameraVectors expected = scene_format_camera(scene.camera);
    const CameraVectors mitsuba = mitsuba_camera_from_xml(sensor);
    // Written with round-trip digits and reconstructed in double: agreement
    // to double rounding, far inside float32's 6e-8 that both renderers use.
    check_close(mitsuba.forward, expected.forward, 1e-13);
    check_close(mitsuba.right, expected.right, 1e-13);
    check_close(mitsuba.up, expected.up, 1e-13);
    const glm::dvec3 origin =
        parse_triple(sensor.one("transform", "to_world").one("lookat").attribute("origin"));
    CHECK(origin == scene.camera.eye);

    // The clipping planes keep the whole scene: nothing is farther than the
    // far plane, and the near plane is a millionth of that.
    const double near = parse_number(sensor.one("float", "near_clip").attribute("value"));
    const double far = parse_number(sensor.one("float", "far_clip").attribute("value"));
    for (const wp::Triangle& t : scene.triangles)
        for (const glm::dvec3& v : t.v)
            CHECK(glm::length(v - scene.camera.eye) < far);
    for (const wp::Sphere& s : scene.spheres)
        CHECK(glm::length(s.center - scene.camera.eye) + s.radius < far);
    CHECK(near > 0.0);
    CHECK(near <= 1e-6 * far * (1 + 1e-12));
}

// ---- Helpers ---------------------------------------------------------------

// Compared as floats, never converted back: GCC 12.2 at -O3 drops the
// double -> float -> double round trip of a dvec3's x and y (seen in this
// file), so `dvec3(float(v.x), ...)` can come out unrounded.
std::array<float, 3> as_float(const glm::dvec3& v) {
    return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

wp::Scene smooth_bunny() {
    std::string text = wp::read_file_text(kScenes + "cornell-bunny.json");
    const std::string file = "\"file\": \"models/stanford-bunny.obj\",";
    REQUIRE(text.find(file) != std::string::npos);
    text.replace(text.find(file), file.size(), file + " \"normals\": \"smooth\",");
    wp::Scene scene = wp::parse_scene(text, kScenes + "smooth-bunny.json");
    REQUIRE(std::count_if(scene.triangles.begin(), scene.triangles.end(),
                          [](const wp::Triangle& t) { return t.has_normals; }) == 69451);
    return scene;
}

wp::Scene small_scene() {
    using namespace wp::test;
    wp::Scene scene;
    scene.source = "built";
    scene.camera = make_camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60, 40, 30);
    const auto white = add_material(scene, wp::MaterialKind::Diffuse, {0.5, 0.6, 0.7});
    add_quad(scene, {-1, -1, -3}, {1, -1, -3}, {1, 1, -3}, {-1, 1, -3}, white);
    return scene;
}

} // namespace

TEST_CASE("mitsuba export: every shape of the hexroom, once", "[scene][mitsuba]") {
    const wp::Scene scene = wp::load_scene(kScenes + "hexroom.json");
    const wp::MitsubaExport exported = wp::export_mitsuba(scene, "hexroom");
    const Element xml = parse_xml(exported.xml);
    REQUIRE(xml.tag == "scene");
    CHECK(exported.warnings.empty());

    // One PLY shape per material that triangles use, one sphere per sphere.
    std::set<std::uint32_t> triangle_materials;
    for (const wp::Triangle& t : scene.triangles)
        triangle_materials.insert(t.material);
    const auto plys = shapes_of_type(xml, "ply");
    REQUIRE(plys.size() == triangle_materials.size());
    REQUIRE(exported.meshes.size() == triangle_materials.size());
    const auto spheres = shapes_of_type(xml, "sphere");
    REQUIRE(spheres.size() == scene.spheres.size());
    CHECK(xml.all("shape").size() == plys.size() + spheres.size());
    CHECK(xml.all("bsdf").size() == scene.materials.size());

    for (std::size_t i = 0; i < plys.size(); ++i) {
        const wp::MitsubaMesh& mesh = exported.meshes[i];
        CHECK(plys[i]->one("string", "filename").attribute("value") == mesh.file_name);
        CHECK(plys[i]->one("ref").attribute("id") == "material-" + std::to_string(mesh.material));
        CHECK(plys[i]->one("boolean", "face_normals").attribute("value") == "true");
        CHECK(mesh.file_name.rfind("hexroom-" + std::to_string(i) + "-", 0) == 0);
        const wp::Material& material = scene.materials[mesh.material];
        CHECK(plys[i]->all("emitter").size() == (material.is_emissive() ? 1u : 0u));
        if (material.is_emissive()) {
            CHECK(plys[i]->one("emitter").attribute("type") == "area");
            CHECK(rgb_value(plys[i]->one("emitter"), "radiance") == material.emission);
        }
    }
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        CHECK(parse_triple(spheres[i]->one("point", "center").attribute("value")) ==
              scene.spheres[i].center);
        CHECK(parse_number(spheres[i]->one("float", "radius").attribute("value")) ==
              scene.spheres[i].radius);
        CHECK(spheres[i]->one("ref").attribute("id") ==
              "material-" + std::to_string(scene.spheres[i].material));
    }

    // The integrator, sampler and film.
    const Element& integrator = xml.one("integrator");
    CHECK(integrator.attribute("type") == "path");
    CHECK(integrator.one("integer", "max_depth").attribute("value") == "-1");
    const Element& sensor = xml.one("sensor");
    CHECK(sensor.one("sampler").attribute("type") == "independent");
    CHECK(sensor.one("sampler").one("integer", "sample_count").attribute("value") == "64");
    const Element& film = sensor.one("film");
    CHECK(film.attribute("type") == "hdrfilm");
    CHECK(film.one("integer", "width").attribute("value") == "800");
    CHECK(film.one("integer", "height").attribute("value") == "800");
    CHECK(film.one("string", "pixel_format").attribute("value") == "rgb");
    CHECK(film.one("rfilter").attribute("type") == "box");

    wp::MitsubaExportOptions options;
    options.sample_count = 7;
    const Element seven = parse_xml(wp::export_mitsuba(scene, "h", options).xml);
    CHECK(seven.one("sensor").one("sampler").one("integer", "sample_count").attribute("value") ==
          "7");
}

TEST_CASE("mitsuba export: the PLY files hold the scene's triangles, winding and all",
          "[scene][mitsuba]") {
    // The bunny's OBJ has no normals: "smooth" gives it shading normals, and
    // its white material is the walls' too, which stay flat.
    const std::string name =
        GENERATE(as<std::string>(), "hexroom", "cornell-box", "cornell-bunny", "smooth-bunny");
    INFO(name);
    const wp::Scene scene =
        name == "smooth-bunny" ? smooth_bunny() : wp::load_scene(kScenes + name + ".json");
    const wp::MitsubaExport exported = wp::export_mitsuba(scene, name);
    wp::test::TempDir dir;
    wp::write_mitsuba(exported, dir / (name + ".xml"));
    CHECK(wp::read_file_text(dir / (name + ".xml")) == exported.xml);

    // The triangles of each material in the scene's order: what each file must hold.
    std::map<std::uint32_t, std::vector<wp::Triangle>> by_material;
    for (const wp::Triangle& t : scene.triangles)
        by_material[t.material].push_back(t);
    std::size_t triangles_written = 0;
    for (const wp::MitsubaMesh& mesh : exported.meshes) {
        const fs::path path = dir / mesh.file_name;
        const std::string text = wp::read_file_text(path);
        CHECK(text.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);

        const wp::TriangleMesh read = wp::load_mesh(path); // wavepath's own PLY reader
        const auto& expected = by_material[mesh.material];
        REQUIRE(read.triangles.size() == expected.size());
        REQUIRE(read.positions.size() == 3 * expected.size());
        CHECK(read.has_normals() == mesh.has_normals);
        bool any_smooth = false;
        for (std::size_t f = 0; f < expected.size(); ++f) {
            const wp::Triangle& t = expected[f];
            any_smooth = any_smooth || t.has_normals;
            const std::array<std::uint32_t, 3> corners = {
                std::uint32_t(3 * f), std::uint32_t(3 * f + 1), std::uint32_t(3 * f + 2)};
            CHECK(read.triangles[f] == corners); // the winding, hence the front face, kept
            for (std::size_t k = 0; k < 3; ++k) {
                // The positions the device traces: float32 of the scene's.
                const glm::dvec3& p = read.positions[3 * f + k];
                const std::array<float, 3> q = as_float(t.v[k]);
                INFO(std::setprecision(17)
                     << "triangle " << f << " corner " << k << ": (" << p.x << ", " << p.y << ", "
                     << p.z << ") against (" << q[0] << ", " << q[1] << ", " << q[2] << ")");
                CHECK(as_float(p) == q);
                CHECK(glm::length(p - t.v[k]) <= 1e-7 * std::max(1.0, glm::length(t.v[k])));
                if (mesh.has_normals) {
                    const glm::dvec3 normal =
                        t.has_normals
                            ? t.normals[k]
                            : glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
                    CHECK(glm::length(read.normals[3 * f + k] - normal) < 1e-6);
                }
            }
        }
        CHECK(mesh.has_normals == any_smooth); // no emissive material has normals here
        triangles_written += read.triangles.size();
    }
    CHECK(triangles_written == scene.triangles.size());
    // A warning exactly when triangles have shading normals (the bunny's OBJ has none).
    const auto smooth = std::count_if(scene.triangles.begin(), scene.triangles.end(),
                                      [](const wp::Triangle& t) { return t.has_normals; });
    CHECK(exported.warnings.size() == (smooth > 0 ? 1u : 0u));
}

TEST_CASE("mitsuba export: the sensor's rays are wavepath's camera rays", "[scene][mitsuba]") {
    SECTION("the hexroom") {
        check_camera(wp::load_scene(kScenes + "hexroom.json"));
    }
    SECTION("the Cornell box") {
        check_camera(wp::load_scene(kScenes + "cornell-box.json"));
    }
    SECTION("tilted, wide, with an up that is not perpendicular to the view") {
        wp::Scene scene = small_scene();
        scene.camera =
            wp::test::make_camera({1, 2, 3}, {-4, 0.5, 7}, {0.3, 1, -0.2}, 50.0, 300, 200);
        check_camera(scene);
    }
    SECTION("tall, far from the origin, narrow") {
        wp::Scene scene = small_scene();
        scene.camera = wp::test::make_camera({1e6, -2e6, 5e5}, {1e6 + 1, -2e6 + 1e-3, 5e5},
                                             {0, 0, 1}, 2.5, 17, 91);
        check_camera(scene);
    }
}

TEST_CASE("mitsuba export: materials map to two-sided BSDFs and one-sided area emitters",
          "[scene][mitsuba]") {
    using namespace wp::test;
    wp::Scene scene = small_scene(); // material 0: diffuse (0.5, 0.6, 0.7)
    const auto mirror = add_material(scene, wp::MaterialKind::Mirror, {0.9, 0.5, 0.25});
    const auto light = add_material(scene, wp::MaterialKind::Emitter, {0, 0, 0}, {5, 6, 7});
    const auto glow = add_material(scene, wp::MaterialKind::Diffuse, {0.1, 0.2, 0.3}, {1, 2, 3});
    add_quad(scene, {-1, -1, -2}, {0, -1, -2}, {0, 0, -2}, {-1, 0, -2}, mirror);
    add_quad(scene, {-1, 1, -2}, {0, 1, -2}, {0, 0.9, -2}, {-1, 0.9, -2}, light);
    add_quad(scene, {0, 1, -2}, {1, 1, -2}, {1, 0.9, -2}, {0, 0.9, -2}, glow);
    scene.spheres.push_back({{0.5, -0.5, -2.5}, 0.25, mirror});
    const Element xml = parse_xml(wp::export_mitsuba(scene, "m").xml);

    const Element& diffuse = bsdf_with_id(xml, "material-0");
    CHECK(diffuse.attribute("type") == "twosided");
    CHECK(diffuse.one("bsdf").attribute("type") == "diffuse");
    CHECK(rgb_value(diffuse.one("bsdf"), "reflectance") == glm::dvec3(0.5, 0.6, 0.7));

    const Element& conductor = bsdf_with_id(xml, "material-1");
    CHECK(conductor.attribute("type") == "twosided");
    CHECK(conductor.one("bsdf").attribute("type") == "conductor");
    CHECK(conductor.one("bsdf").one("string", "material").attribute("value") == "none");
    CHECK(rgb_value(conductor.one("bsdf"), "specular_reflectance") == glm::dvec3(0.9, 0.5, 0.25));

    const Element& black = bsdf_with_id(xml, "material-2");
    CHECK(black.attribute("type") == "diffuse");
    CHECK(rgb_value(black, "reflectance") == glm::dvec3(0.0));

    CHECK(rgb_value(bsdf_with_id(xml, "material-3").one("bsdf"), "reflectance") ==
          glm::dvec3(0.1, 0.2, 0.3));

    // Emitters on exactly the meshes whose material emits, with its radiance.
    const auto plys = shapes_of_type(xml, "ply");
    REQUIRE(plys.size() == 4);
    std::map<std::string, const Element*> by_material;
    for (const Element* shape : plys)
        by_material[shape->one("ref").attribute("id")] = shape;
    REQUIRE(by_material.size() == 4);
    CHECK(by_material["material-0"]->all("emitter").empty());
    CHECK(by_material["material-1"]->all("emitter").empty());
    CHECK(rgb_value(by_material["material-2"]->one("emitter"), "radiance") == glm::dvec3(5, 6, 7));
    CHECK(rgb_value(by_material["material-3"]->one("emitter"), "radiance") == glm::dvec3(1, 2, 3));
    const auto spheres = shapes_of_type(xml, "sphere");
    REQUIRE(spheres.size() == 1);
    CHECK(spheres[0]->one("ref").attribute("id") == "material-1");
    CHECK(spheres[0]->all("emitter").empty());
}

TEST_CASE("mitsuba export: emissive triangles are written flat, smooth ones with a warning",
          "[scene][mitsuba]") {
    using namespace wp::test;
    wp::Scene scene = small_scene();
    const auto glow = add_material(scene, wp::MaterialKind::Diffuse, {0.5, 0.5, 0.5}, {1, 1, 1});
    const auto light = add_material(scene, wp::MaterialKind::Emitter, {0, 0, 0}, {4, 4, 4});
    const glm::dvec3 bent = glm::normalize(glm::dvec3(0.2, 0.1, 1.0));
    for (std::uint32_t material : {0u, std::uint32_t(glow), std::uint32_t(light)}) {
        wp::Triangle t{{glm::dvec3(-1, -1, -2), glm::dvec3(1, -1, -2), glm::dvec3(0, 1, -2)},
                       material};
        t.has_normals = true;
        t.normals = {bent, bent, bent};
        scene.triangles.push_back(t);
    }
    const wp::MitsubaExport exported = wp::export_mitsuba(scene, "s");
    REQUIRE(exported.meshes.size() == 3);
    CHECK(exported.meshes[0].has_normals);       // diffuse: shaded by its normals
    CHECK_FALSE(exported.meshes[1].has_normals); // diffuse and emissive: flat
    CHECK_FALSE(exported.meshes[2].has_normals); // an emitter reflects nothing: flat, silently
    REQUIRE(exported.warnings.size() == 2);
    CHECK(exported.warnings[0].find("material 'material1': 1 triangles with shading normals are "
                                    "emissive; they are exported flat") == 0);
    CHECK(exported.warnings[1].find("1 triangles have shading normals") == 0);
    CHECK(exported.warnings[1].find("shadow-terminator fix") != std::string::npos);

    const Element xml = parse_xml(exported.xml);
    const auto plys = shapes_of_type(xml, "ply");
    REQUIRE(plys.size() == 3);
    CHECK(plys[0]->one("boolean", "face_normals").attribute("value") == "false");
    CHECK(plys[1]->one("boolean", "face_normals").attribute("value") == "true");
    CHECK(plys[2]->one("boolean", "face_normals").attribute("value") == "true");
}

TEST_CASE("mitsuba export: any material name gives well-formed XML and a plain file name",
          "[scene][mitsuba]") {
    wp::Scene scene = small_scene();
    scene.materials[0].name = "a--b <&> \"q\" 'x'/../\xc3\xa9\x01\n-";
    scene.source = "dir/with & and --/scene.json";
    const wp::MitsubaExport exported = wp::export_mitsuba(scene, "out");
    const Element xml = parse_xml(exported.xml); // expat: well-formed, comments included
    REQUIRE(exported.meshes.size() == 1);
    const std::string& file = exported.meshes[0].file_name;
    CHECK(file.rfind("out-0-a__b", 0) == 0);
    CHECK(std::all_of(file.begin(), file.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    }));
    CHECK(shapes_of_type(xml, "ply")[0]->one("string", "filename").attribute("value") == file);
}

TEST_CASE("mitsuba export: a mesh that cannot be written leaves no XML", "[scene][mitsuba]") {
    const wp::Scene scene = wp::load_scene(kScenes + "cornell-box.json");
    const wp::MitsubaExport exported = wp::export_mitsuba(scene, "box");
    wp::test::TempDir dir;
    // A directory where the last mesh should go: writing it fails.
    fs::create_directory(dir / exported.meshes.back().file_name);
    CHECK_THROWS_AS(wp::write_mitsuba(exported, dir / "box.xml"), wp::FileError);
    CHECK_FALSE(fs::exists(dir / "box.xml"));
}
