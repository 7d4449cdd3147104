// Mitsuba's shapegroup and instance in the XML reader: the agreement scene
// (tests/data/mitsuba/instances.xml) read as written, and bad input refused
// with one line naming the file, the place and the element.
#include <catch2/catch.hpp>

#include <string>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "scene/load.hpp"
#include "scene/mitsuba_export.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kSensor = R"(<sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <emitter type="constant"/>)";

std::string error_of(const wp::test::TempDir& dir, const std::string& body) {
    wp::test::write_text(dir / "s.xml", "<scene version=\"3.0.0\">\n    " + kSensor + "\n    " +
                                            body + "\n</scene>\n");
    try {
        (void)wp::load_scene(dir / "s.xml");
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

} // namespace

TEST_CASE("Mitsuba reader: shapegroups and instances of the agreement scene",
          "[scene][mitsuba][instances]") {
    const wp::Scene s = wp::load_scene(WAVEPATH_SOURCE_DIR "/tests/data/mitsuba/instances.xml");
    REQUIRE(s.shape_groups.size() == 2);
    CHECK(s.shape_groups[0].name == "block");
    CHECK(s.shape_groups[1].name == "gem");
    CHECK(s.shape_groups[1].triangles.size() == 12); // one cube
    // block: a cube, a rectangle and the OBJ tile's triangles, in object space
    CHECK(s.shape_groups[0].triangles.size() > 14);
    REQUIRE(s.instances.size() == 5);
    const int groups[] = {0, 0, 0, 1, 1};
    for (int i = 0; i < 5; ++i)
        CHECK(s.instances[i].group == std::uint32_t(groups[i]));
    // The second block and the second gem are mirrored.
    for (int i = 0; i < 5; ++i)
        CHECK((glm::determinant(glm::dmat3(s.instances[i].to_world)) < 0.0) == (i == 1 || i == 4));
    // <scale value="0.6"/> then <translate x="0.2" z="-2"/>
    const glm::dvec4 p = s.instances[2].to_world * glm::dvec4(1, 1, 1, 1);
    CHECK(p.x == Approx(0.8));
    CHECK(p.y == Approx(0.6));
    CHECK(p.z == Approx(-1.4));
    // Only the floor and the light are plain shapes.
    CHECK(s.triangles.size() == 4);
}

TEST_CASE("Mitsuba reader: bad shapegroups and instances are one line with the place",
          "[scene][mitsuba][instances][errors]") {
    wp::test::TempDir dir;
    const std::string group =
        R"(<shape type="shapegroup" id="g"><shape type="rectangle"/></shape>)";
    struct Case {
        const char* what;
        std::string body;
        std::string fragment;
    };
    const std::vector<Case> cases{
        {"emitter in a group",
         R"(<shape type="shapegroup" id="lamp"><shape type="rectangle"><emitter type="area"/></shape></shape>)",
         "<emitter type=\"area\">: an emitter inside shapegroup 'lamp'"},
        {"sphere in a group",
         R"(<shape type="shapegroup" id="balls"><shape type="sphere"/></shape>)",
         "<shape type=\"sphere\">: a sphere inside shapegroup 'balls' is not supported"},
        {"nested group", R"(<shape type="shapegroup" id="outer">)" + group + "</shape>",
         "not supported inside shapegroup 'outer'"},
        {"unknown group", R"(<shape type="instance"><ref id="nope"/></shape>)", "nope"},
        {"instance without a group", R"(<shape type="instance"/>)",
         "an instance without its shapegroup"},
        {"instance of a plain shape",
         R"(<shape type="rectangle" id="r"/><shape type="instance"><ref id="r"/></shape>)",
         "an instance takes exactly one shapegroup"},
        {"singular to_world",
         group +
             R"(<shape type="instance"><ref id="g"/><transform name="to_world"><matrix value="1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1"/></transform></shape>)",
         "s.xml:"},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        const std::string message = error_of(dir, c.body);
        CHECK(message.find(c.fragment) != std::string::npos);
        CHECK(message.find("s.xml:") != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("Mitsuba export: shapegroups and instances written back read as the same scene",
          "[scene][mitsuba][instances]") {
    const wp::Scene original =
        wp::load_scene(WAVEPATH_SOURCE_DIR "/tests/data/mitsuba/instances.xml");
    wp::test::TempDir dir;
    wp::write_mitsuba(wp::export_mitsuba(original, "round"), dir / "round.xml");
    const std::string xml = wp::test::read_text(dir / "round.xml");
    CHECK(xml.find("<shape type=\"shapegroup\" id=\"group-0-block\">") != std::string::npos);
    CHECK(xml.find("<shape type=\"instance\">") != std::string::npos);
    const wp::Scene back = wp::load_scene(dir / "round.xml");
    REQUIRE(back.shape_groups.size() == original.shape_groups.size());
    REQUIRE(back.instances.size() == original.instances.size());
    for (std::size_t g = 0; g < back.shape_groups.size(); ++g) {
        const auto& a = original.shape_groups[g].triangles;
        const auto& b = back.shape_groups[g].triangles;
        REQUIRE(a.size() == b.size());
        // The PLY files hold float32 vertices: the same triangles to float's precision.
        double largest = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int k = 0; k < 3; ++k)
                largest = std::max(largest, glm::length(a[i].v[k] - b[i].v[k]));
        CHECK(largest < 1e-6);
    }
    for (std::size_t i = 0; i < back.instances.size(); ++i) {
        CHECK(back.instances[i].group == original.instances[i].group);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                CHECK(back.instances[i].to_world[c][r] ==
                      Approx(original.instances[i].to_world[c][r]).margin(1e-15));
    }
    CHECK(back.triangles.size() == original.triangles.size());
}

TEST_CASE("Mitsuba reader: --lenient leaves out a shape wavepath has not inside a shapegroup",
          "[scene][mitsuba][instances]") {
    wp::test::TempDir dir;
    CHECK(error_of(dir, R"(<shape type="shapegroup" id="g"><shape type="cylinder"/></shape>)")
              .find("unsupported shape type 'cylinder'") != std::string::npos);
    wp::test::write_text(
        dir / "s.xml",
        "<scene version=\"3.0.0\">\n    " + kSensor +
            "\n    <shape type=\"shapegroup\" id=\"g\"><shape type=\"cylinder\"/><shape "
            "type=\"rectangle\"/></shape>\n    <shape type=\"instance\"><ref id=\"g\"/></shape>\n"
            "</scene>\n");
    wp::SceneReadOptions options;
    options.lenient = true;
    const wp::Scene s = wp::load_scene(dir / "s.xml", options);
    REQUIRE(s.shape_groups.size() == 1);
    CHECK(s.shape_groups[0].triangles.size() == 2); // the rectangle
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0].find("<shape type=\"cylinder\">: left out") != std::string::npos);
}
