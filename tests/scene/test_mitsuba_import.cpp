// The Mitsuba reader (scene/mitsuba/load_mitsuba.hpp) on small scenes whose
// result is worked out by hand: the order of transform steps, rotations,
// flip_normals, the cube and the disk, a sphere's to_world, the sensor's
// frame and field of view, <default>/$name, <include>, <ref>, and the bad
// input table: each one line with the file, line and column.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/mitsuba_export.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kSensor = R"(<sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="32"/></film>
    </sensor>)";

const std::string kLight = R"(<shape type="rectangle">
        <transform name="to_world"><translate z="-2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="1"/></emitter>
    </shape>)";

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

// A scene file of `body` (after the sensor and a light) in `dir`.
wp::Scene load(const wp::test::TempDir& dir, const std::string& body,
               const std::string& name = "s.xml") {
    write(dir / name, "<scene version=\"3.0.0\">\n    " + kSensor + "\n    " + kLight + "\n    " +
                          body + "\n</scene>\n");
    return wp::load_scene(dir / name);
}

glm::dvec3 normal_of(const wp::Triangle& t) {
    return glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
}

void check_near(const glm::dvec3& a, const glm::dvec3& b) {
    INFO("(" << a.x << ", " << a.y << ", " << a.z << ") against (" << b.x << ", " << b.y << ", "
             << b.z << ")");
    CHECK(glm::length(a - b) < 1e-12);
}

std::string repeated(const std::string& text, int times) {
    std::string out;
    for (int i = 0; i < times; ++i)
        out += text;
    return out;
}

constexpr const char* kNested = "<bsdf type=\"twosided\">";

std::string error_of(const wp::test::TempDir& dir, const std::string& text) {
    write(dir / "bad.xml", text);
    try {
        (void)wp::load_scene(dir / "bad.xml");
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

} // namespace

TEST_CASE("mitsuba import: transform steps apply in the order written",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    // The light is triangles 0 and 1; the rectangle's corner (1, 1, 0).
    const wp::Scene a = load(dir, R"(<shape type="rectangle"><transform name="to_world">
        <scale value="2"/><translate x="1"/></transform></shape>)");
    const wp::Scene b = load(dir, R"(<shape type="rectangle"><transform name="to_world">
        <translate x="1"/><scale value="2"/></transform></shape>)");
    REQUIRE(a.triangles.size() == 4);
    check_near(a.triangles[2].v[2], {3, 2, 0}); // (1, 1, 0) * 2 + (1, 0, 0)
    check_near(b.triangles[2].v[2], {4, 2, 0}); // ((1, 1, 0) + (1, 0, 0)) * 2
    // Mitsuba's default BSDF, a diffuse 0.5, with no twosided: a warning.
    CHECK(a.materials[a.triangles[2].material].reflectance == glm::dvec3(0.5));
}

TEST_CASE("mitsuba import: rotations are right-handed, flip_normals and mirrors turn the front",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene s = load(dir, R"(<shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="90"/></transform></shape>
    <shape type="rectangle"><boolean name="flip_normals" value="true"/></shape>
    <shape type="rectangle"><transform name="to_world"><scale x="-1"/></transform></shape>
    <shape type="disk"><transform name="to_world"><scale x="-1"/></transform></shape>)");
    REQUIRE(s.triangles.size() == 8 + 256);
    check_near(normal_of(s.triangles[2]), {0, -1, 0}); // +z turned 90 degrees about +x
    check_near(normal_of(s.triangles[4]), {0, 0, -1});
    // A mirror turns a rectangle round, as Mitsuba 3.9.1 does (its front is
    // the winding of the mirrored corners); the disk keeps its front.
    check_near(normal_of(s.triangles[6]), {0, 0, -1});
    for (std::size_t i = 8; i < s.triangles.size(); ++i)
        check_near(normal_of(s.triangles[i]), {0, 0, 1});
}

TEST_CASE("mitsuba import: the cube faces out, the disk is a fan of its area",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene s = load(dir, R"(<shape type="cube"><transform name="to_world">
        <translate x="3"/></transform></shape>
    <shape type="disk"><transform name="to_world"><scale value="2"/></transform></shape>)");
    double cube_area = 0.0, disk_area = 0.0;
    int cube = 0, disk = 0;
    for (std::size_t i = 2; i < s.triangles.size(); ++i) {
        const wp::Triangle& t = s.triangles[i];
        const double area = 0.5 * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
        const glm::dvec3 centre = (t.v[0] + t.v[1] + t.v[2]) / 3.0;
        if (centre.x > 1.5) {
            ++cube;
            cube_area += area;
            CHECK(glm::dot(normal_of(t), centre - glm::dvec3(3, 0, 0)) > 0.0);
        } else {
            ++disk;
            disk_area += area;
            check_near(normal_of(t), {0, 0, 1});
        }
    }
    CHECK(cube == 12);
    CHECK(cube_area == Approx(24.0).epsilon(1e-12));
    CHECK(disk == 256);
    const double fan = 0.5 * 256 * 4.0 * std::sin(2.0 * M_PI / 256); // radius 2
    CHECK(disk_area == Approx(fan).epsilon(1e-12));
    CHECK(disk_area == Approx(4.0 * M_PI).epsilon(2e-4));
}

TEST_CASE("mitsuba import: a sphere's to_world moves and scales it", "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene s = load(dir, R"(<shape type="sphere">
        <point name="center" x="1"/><float name="radius" value="0.5"/>
        <transform name="to_world"><rotate z="1" angle="90"/><scale value="3"/>
            <translate y="1"/></transform></shape>)");
    REQUIRE(s.spheres.size() == 1);
    check_near(s.spheres[0].center, {0, 4, 0}); // (1,0,0) -> (0,1,0) -> (0,3,0) -> (0,4,0)
    CHECK(s.spheres[0].radius == Approx(1.5).epsilon(1e-15));
}

TEST_CASE("mitsuba import: the sensor's frame and its field of view along x",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene s = load(dir, R"(<shape type="rectangle"/>)");
    check_near(s.camera.eye, {0, 0, 5});
    check_near(glm::normalize(s.camera.look_at - s.camera.eye), {0, 0, -1});
    // fov 60 along x of a 48 x 32 image: tan(v / 2) = tan(30 degrees) * 32 / 48.
    const double vertical = 2.0 * std::atan(std::tan(M_PI / 6.0) * 32.0 / 48.0) * 180.0 / M_PI;
    CHECK(s.camera.vertical_fov_degrees == Approx(vertical).epsilon(1e-12));
    CHECK(s.camera.filter == wp::FilterKind::Gaussian); // hdrfilm's default
}

TEST_CASE("mitsuba import: <default>, $name, <include> and <ref>", "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    write(dir / "materials.xml", R"(<scene version="3.0.0">
    <bsdf type="twosided" id="paint"><bsdf type="diffuse">
        <rgb name="reflectance" value="$paint"/></bsdf></bsdf>
</scene>)");
    const wp::Scene s = load(dir, R"(<default name="paint" value="0.25, 0.5, 0.75"/>
    <include filename="materials.xml"/>
    <shape type="rectangle"><ref id="paint"/></shape>
    <shape type="cube"><ref id="paint"/></shape>)");
    REQUIRE(s.triangles.size() == 2 + 2 + 12);
    const std::uint32_t m = s.triangles[2].material;
    CHECK(s.triangles[15].material == m); // one BSDF, one material
    CHECK(s.materials[m].reflectance == glm::dvec3(0.25, 0.5, 0.75));
    CHECK(s.materials[m].name == "paint");
    CHECK(s.warnings.empty());  // twosided: no one-sided warning
    CHECK(s.files.size() == 1); // the include, which outputs must not overwrite
}

TEST_CASE("mitsuba import: a <ref> before its element, <path>, a top-level area emitter",
          "[scene][mitsuba][import]") {
    // As mitsuba-data's scenes have them: cbox-rgb.xml's luminaire refers to
    // an area emitter declared later, at the top level; hello.xml finds its
    // mesh through <path value="../common"/>.
    wp::test::TempDir dir;
    fs::create_directories(dir / "common" / "meshes");
    fs::create_directories(dir / "scenes");
    write(dir / "common" / "meshes" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const wp::Scene s = load(dir, R"(<path value="../common"/>
    <shape type="obj"><string name="filename" value="meshes/tri.obj"/>
        <ref id="paint"/><ref id="glow"/></shape>
    <bsdf type="diffuse" id="paint"><rgb name="reflectance" value="0.25"/></bsdf>
    <emitter type="area" id="glow"><rgb name="radiance" value="2, 3, 4"/></emitter>)",
                             "scenes/s.xml");
    const wp::Triangle& t = s.triangles.back();
    CHECK(t.v[1] == glm::dvec3(1.0, 0.0, 0.0));
    CHECK(s.materials[t.material].reflectance == glm::dvec3(0.25));
    CHECK(s.materials[t.material].emission == glm::dvec3(2.0, 3.0, 4.0));
}

TEST_CASE("mitsuba import: point, spot, directional and constant emitters at the top level",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene s = load(dir, R"(<emitter type="point">
        <point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="4, 5, 6"/></emitter>
    <emitter type="point"><transform name="to_world"><translate x="-1"/></transform></emitter>
    <emitter type="spot"><float name="cutoff_angle" value="40"/>
        <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="1, 0, 0"/></transform>
    </emitter>
    <emitter type="directional"><vector name="direction" value="0, -2, 0"/>
        <rgb name="irradiance" value="2"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>)");
    REQUIRE(s.emitters.size() == 5);
    CHECK(s.emitters[0].kind == wp::EmitterKind::Point);
    check_near(s.emitters[0].position, {1, 2, 3});
    CHECK(s.emitters[0].value == glm::dvec3(4, 5, 6));
    check_near(s.emitters[1].position, {-1, 0, 0});
    CHECK(s.emitters[1].value == glm::dvec3(1.0)); // Mitsuba's default intensity
    CHECK(s.emitters[2].kind == wp::EmitterKind::Spot);
    check_near(s.emitters[2].position, {0, 3, 0});
    check_near(s.emitters[2].direction, {0, -1, 0}); // to_world's z axis
    CHECK(s.emitters[2].cutoff_angle == 40.0);
    CHECK(s.emitters[2].beam_width == 30.0); // Mitsuba's default: 3/4 of the cutoff
    CHECK(s.emitters[3].kind == wp::EmitterKind::Directional);
    check_near(s.emitters[3].direction, {0, -1, 0});
    CHECK(s.emitters[3].value == glm::dvec3(2.0));
    CHECK(s.emitters[4].kind == wp::EmitterKind::Constant);
    CHECK(s.emitters[4].value == glm::dvec3(0.5));
}

TEST_CASE("mitsuba import: serialized shapes by shape_index, placed and flipped",
          "[scene][mitsuba][import][serialized]") {
    wp::test::TempDir dir;
    fs::copy_file(fs::path(WAVEPATH_SOURCE_DIR) / "tests/data/meshes/two-meshes.serialized",
                  dir / "m.serialized");
    // Mesh 1 of the file (its vertex 0 at (2, 0, 0), no normals: smooth ones
    // are computed, as Mitsuba does), moved by to_world; mesh 0 with its
    // file normals, flipped; mesh 0 again with face_normals.
    const wp::Scene s = load(dir, R"(<shape type="serialized">
        <string name="filename" value="m.serialized"/><integer name="shape_index" value="1"/>
        <transform name="to_world"><translate z="-1"/></transform></shape>
    <shape type="serialized"><string name="filename" value="m.serialized"/>
        <boolean name="flip_normals" value="true"/></shape>
    <shape type="serialized"><string name="filename" value="m.serialized"/>
        <boolean name="face_normals" value="true"/></shape>)");
    REQUIRE(s.triangles.size() == 2 + 6);
    check_near(s.triangles[2].v[0], {2, 0, -1});
    CHECK(s.triangles[2].has_normals);
    // Vertex 3 lies in triangle (1, 3, 2) alone: its smooth normal is that
    // face's, (-1, -1, 2) / sqrt(6) (Mitsuba 3.9.1 gives the same).
    check_near(s.triangles[3].normals[1], glm::normalize(glm::dvec3(-1, -1, 2)));
    // flip_normals turns the winding and the file's normals round.
    check_near(normal_of(s.triangles[4]), {0, 0, -1});
    check_near(s.triangles[4].normals[0], {0, 0, -1});
    CHECK_FALSE(s.triangles[6].has_normals);
    check_near(normal_of(s.triangles[6]), {0, 0, 1});
    // A texture coordinate of the file, as it is.
    CHECK(s.triangles[4].uvs[0] == glm::dvec2(0, 0));
}

TEST_CASE("mitsuba import: the path integrator's hide_emitters, read and exported",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene shown = load(dir, R"(<integrator type="path"/>)");
    CHECK_FALSE(shown.hide_emitters);
    const wp::Scene hidden = load(
        dir,
        R"(<integrator type="path"><boolean name="hide_emitters" value="true"/></integrator>)");
    CHECK(hidden.hide_emitters);
    // export-mitsuba writes it, and the export reads back with it.
    for (const wp::Scene* scene : {&shown, &hidden}) {
        const wp::MitsubaExport out = wp::export_mitsuba(*scene, "back");
        wp::write_mitsuba(out, dir / "back.xml");
        CHECK(wp::load_scene(dir / "back.xml").hide_emitters == scene->hide_emitters);
    }
}

TEST_CASE("mitsuba import: the path integrator's max_depth and rr_depth, read and exported",
          "[scene][mitsuba][import]") {
    wp::test::TempDir dir;
    const wp::Scene plain = load(dir, R"(<integrator type="path"/>)");
    CHECK(plain.mitsuba_depths);
    CHECK(plain.max_depth == -1); // Mitsuba's default: no limit
    CHECK(plain.rr_depth == 0);   // none given: wavepath's roulette
    const wp::Scene set = load(dir, R"(<integrator type="path"><integer name="max_depth" value="3"/>
        <integer name="rr_depth" value="2"/></integrator>)");
    CHECK(set.max_depth == 3);
    CHECK(set.rr_depth == 2);
    CHECK(load(dir, "").mitsuba_depths); // no <integrator>: Mitsuba's path, -1
    // export-mitsuba writes them back, and the export reads back with them;
    // a JSON scene has neither (-1, and no rr_depth).
    for (const wp::Scene* scene : {&plain, &set}) {
        wp::write_mitsuba(wp::export_mitsuba(*scene, "back"), dir / "back.xml");
        const wp::Scene back = wp::load_scene(dir / "back.xml");
        CHECK(back.max_depth == scene->max_depth);
        CHECK(back.rr_depth == scene->rr_depth);
    }
    const wp::Scene json = wp::load_scene(WAVEPATH_SOURCE_DIR "/scenes/cornell-box.json");
    CHECK_FALSE(json.mitsuba_depths);
    CHECK(json.max_depth == -1);
}

TEST_CASE("mitsuba import: bad input is one line with the file, line and column",
          "[scene][mitsuba][import][errors]") {
    wp::test::TempDir dir;
    const std::string bad = (dir / "bad.xml").string();
    fs::copy_file(fs::path(WAVEPATH_SOURCE_DIR) / "tests/data/meshes/two-meshes.serialized",
                  dir / "m.serialized");
    struct Case {
        const char* what;
        std::string xml;
        std::string where; // "L:C"
        std::string fragment;
    };
    const std::string head = "<scene version=\"3.0.0\">\n";
    const std::vector<Case> cases{
        {"malformed XML", head + "<shape type=\"cube\">\n</scene>\n", "3:3", "malformed XML"},
        {"not a scene", "<sensor type=\"perspective\"/>\n", "1:1", "root element must be <scene>"},
        {"old version", "<scene version=\"0.6.0\">\n</scene>\n", "1:1", "versions 2.x and 3.x"},
        {"unsupported shape", head + "  <shape type=\"cylinder\"/>\n</scene>\n", "2:3",
         "unsupported shape type 'cylinder' (wavepath reads obj, ply, serialized"},
        {"unsupported BSDF",
         head + kSensor + "\n<shape type=\"cube\"><bsdf type=\"hair\"/></shape></scene>", "7:20",
         "unsupported BSDF type 'hair' (wavepath reads diffuse"},
        {"anisotropic roughplastic",
         head + kSensor +
             "\n<shape type=\"cube\"><bsdf type=\"roughplastic\">\n"
             "<float name=\"alpha_u\" value=\"0.1\"/><float name=\"alpha_v\" value=\"0.2\"/>"
             "</bsdf></shape></scene>",
         "8:1", "roughplastic's roughness is isotropic"},
        {"unsupported emitter", head + "<emitter type=\"projector\"/>\n</scene>\n", "2:1",
         "unsupported emitter at the scene's top level (wavepath reads point, spot"},
        {"zero spot cutoff",
         head + "<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"0\"/></emitter>\n"
                "</scene>\n",
         "2:22", "must be in (0, 180] degrees (a zero cutoff lights nothing), got 0"},
        {"negative intensity",
         head + "<emitter type=\"point\"><rgb name=\"intensity\" value=\"1, -1, 1\"/></emitter>\n"
                "</scene>\n",
         "2:23", "must be in [0, 1e+30], got -1"},
        {"position and to_world",
         head + "<emitter type=\"point\"><point name=\"position\" x=\"1\"/>"
                "<transform name=\"to_world\"><translate x=\"1\"/></transform></emitter>\n"
                "</scene>\n",
         "2:23", "give either position or to_world"},
        {"zero sun direction",
         head + "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, 0\"/>"
                "</emitter>\n</scene>\n",
         "2:29", "gives no direction"},
        {"two skies",
         head + "<emitter type=\"constant\"/>\n<emitter type=\"constant\"/>\n</scene>\n", "3:1",
         "a second environment (constant or envmap emitter)"},
        {"unknown parameter",
         head + "<shape type=\"cube\">\n  <float name=\"radius\" value=\"1\"/>"
                "</shape></scene>",
         "3:3", "does not support the parameter 'radius' of <shape type=\"cube\">"},
        {"wrong kind",
         head + "<shape type=\"sphere\"><string name=\"radius\" value=\"1\"/>"
                "</shape></scene>",
         "2:22", "must be <float> or <integer>, not <string>"},
        {"undefined $name",
         head + "<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/>"
                "</shape></scene>",
         "2:22", "undefined parameter $r"},
        {"unknown ref", head + "<shape type=\"cube\"><ref id=\"nope\"/></shape></scene>", "2:20",
         "refers to id 'nope', which no element declares"},
        {"missing mesh",
         head + "<shape type=\"obj\">\n<string name=\"filename\" value=\"no.obj\"/>"
                "</shape></scene>",
         "3:1", "no.obj"},
        {"serialized: a negative shape_index",
         head + "<shape type=\"serialized\"><string name=\"filename\" value=\"m.serialized\"/>"
                "\n<integer name=\"shape_index\" value=\"-1\"/></shape></scene>",
         "3:1", "must be a mesh's index in the file (0 or more), got -1"},
        {"serialized: shape_index past the file's meshes",
         head + "<shape type=\"serialized\">\n<string name=\"filename\" value=\"m.serialized\"/>"
                "<integer name=\"shape_index\" value=\"2\"/></shape></scene>",
         "3:1", "m.serialized: shape_index 2 is out of range: the file holds 2 meshes (0 to 1)"},
        {"include cycle", head + "<include filename=\"bad.xml\"/>\n</scene>\n", "2:1",
         "include cycle"},
        {"non-uniform sphere",
         head + "<shape type=\"sphere\"><transform name=\"to_world\">"
                "<scale x=\"2\"/></transform></shape></scene>",
         "2:22", "must scale uniformly"},
        {"mirrored camera",
         head + "<sensor type=\"perspective\"><transform name=\"to_world\">"
                "<scale x=\"-1\"/></transform></sensor></scene>",
         "2:28", "mirrors the image"},
        {"spectrum pairs: wavelengths going down",
         head +
             "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
             "<spectrum name=\"reflectance\" value=\"500:0.1, 400:0.5\"/></bsdf></shape></scene>",
         "3:1", "the wavelengths must increase, but 400 follows 500"},
        {"spectrum pairs: one pair",
         head + "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
                "<spectrum name=\"reflectance\" value=\"500:0.1\"/></bsdf></shape></scene>",
         "3:1", "expected wavelength:value pairs (at least two"},
        {"spectrum pairs: a value missing",
         head + "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
                "<spectrum name=\"reflectance\" value=\"400:0.1, 500:\"/></bsdf></shape></scene>",
         "3:1", "expected wavelength:value pairs"},
        {"a forward ref to itself",
         head + "<bsdf type=\"twosided\" id=\"loop\">\n<ref id=\"loop\"/></bsdf></scene>", "3:1",
         "an object cannot contain itself"},
        {"a <path> that is not there", head + "<path value=\"no-such-folder\"/></scene>", "2:1",
         "no-such-folder' does not exist"},
        {"the direct integrator",
         head + "<integrator type=\"direct\"/>\n<sensor type=\"perspective\"/></scene>", "2:1",
         "unsupported integrator 'direct' (wavepath renders with Mitsuba's path integrator"},
        {"reflectance range",
         head + "<shape type=\"cube\"><bsdf type=\"diffuse\">\n"
                "<rgb name=\"reflectance\" value=\"2\"/></bsdf></shape></scene>",
         "3:1", "must be in [0, 1], got 2"},
        {"thinlens without aperture_radius",
         head + "<sensor type=\"thinlens\"><float name=\"focus_distance\" value=\"2\"/>"
                "</sensor></scene>",
         "2:1", "needs aperture_radius"},
        {"objects nested too deep (a hostile file: 10^5 levels overflowed the stack)",
         head + repeated(kNested, 100000) + repeated("</bsdf>", 100000) + "</scene>",
         "2:" + std::to_string(1 + 64 * std::string(kNested).size()), "nested more than 64 deep"},
        {"no sensor", head + "<shape type=\"cube\"/></scene>", "1:1", "has no <sensor>"},
        {"max_depth 0 (Mitsuba renders black)",
         head + "<integrator type=\"path\">\n  <integer name=\"max_depth\" value=\"0\"/>"
                "</integrator></scene>",
         "3:3",
         "max_depth\">: must be -1 (no limit) or in [1, 1048576] (the longest path in "
         "edges, the camera ray included), got 0"},
        {"max_depth -2",
         head + "<integrator type=\"path\">\n  <integer name=\"max_depth\" value=\"-2\"/>"
                "</integrator></scene>",
         "3:3", "must be -1 (no limit) or in [1, 1048576]"},
        {"max_depth not an integer",
         head + "<integrator type=\"path\">\n  <integer name=\"max_depth\" value=\"2.5\"/>"
                "</integrator></scene>",
         "3:3", "2.5"},
        {"max_depth as a float",
         head + "<integrator type=\"path\">\n  <float name=\"max_depth\" value=\"3\"/>"
                "</integrator></scene>",
         "3:3", "must be <integer>, not <float>"},
        {"rr_depth 0 (Mitsuba refuses it)",
         head + "<integrator type=\"path\">\n  <integer name=\"rr_depth\" value=\"0\"/>"
                "</integrator></scene>",
         "3:3", "rr_depth\">: must be in [1, 1048576], got 0"},
    };
    for (const Case& c : cases) {
        INFO(c.what << "\n" << c.xml);
        const std::string message = error_of(dir, c.xml);
        INFO(message);
        CHECK(message.rfind(bad + ":" + c.where + ": ", 0) == 0);
        CHECK(message.find(c.fragment) != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}
