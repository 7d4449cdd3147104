// Shape groups and instances in the JSON format: read as defined (the group's
// triangles in object space, each instance's to_world as composed), and every
// bad input refused with one line naming the field.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include <glm/mat4x4.hpp>

#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "support/scene_json.hpp"

namespace {

const std::string kQuad =
    R"({"type": "quad", "material": "white", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]})";
const std::string kGroup = R"({"type": "shapegroup", "id": "tile", "shapes": [)" + kQuad + "]}";

std::string with_shapes(const std::string& shapes) {
    return wp::test::scene_json(wp::test::kSceneCamera, wp::test::kSceneMaterials, shapes);
}

std::string error_of(const std::string& json) {
    try {
        (void)wp::parse_scene(json, "test.json");
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

} // namespace

TEST_CASE("instances: a shape group is read once in object space and placed by its instances",
          "[scene][load][instances]") {
    const wp::Scene s = wp::parse_scene(with_shapes("[" + kGroup + R"(,
            {"type": "instance", "shapegroup": "tile"},
            {"type": "instance", "shapegroup": "tile", "to_world": [{"scale": [2, 1, 1]}, {"translate": [0, 0, 5]}]},
            {"type": "instance", "shapegroup": "tile", "to_world": [{"scale": [-1, 1, 1]}]}])"),
                                        "test.json");
    CHECK(s.triangles.empty());
    REQUIRE(s.shape_groups.size() == 1);
    CHECK(s.shape_groups[0].name == "tile");
    REQUIRE(s.shape_groups[0].triangles.size() == 2);
    CHECK(s.shape_groups[0].triangles[0].v[2] == glm::dvec3(1, 1, 0)); // as written: object space
    REQUIRE(s.instances.size() == 3);
    CHECK(s.instances[0].to_world == glm::dmat4(1.0));
    // scale then translate: x' = 2 x, z' = z + 5
    const glm::dvec4 p = s.instances[1].to_world * glm::dvec4(1, 1, 0, 1);
    CHECK(p == glm::dvec4(2, 1, 5, 1));
    CHECK(s.instances[2].to_world[0][0] == -1.0);
}

TEST_CASE("instances: bad groups and instances are refused with one line naming the field",
          "[scene][load][instances][errors]") {
    struct Case {
        const char* what;
        std::string shapes;
        std::string fragment; // in the message, after "test.json: "
    };
    const std::vector<Case> cases{
        {"unknown group", R"([)" + kQuad + R"(, {"type": "instance", "shapegroup": "nope"}])",
         "/shapes/1/shapegroup: unknown shape group 'nope' (none is defined)"},
        {"instance before its group",
         R"([{"type": "instance", "shapegroup": "tile"}, )" + kGroup + "]",
         "/shapes/0/shapegroup: unknown shape group 'tile'"},
        {"emitter in a group",
         R"([{"type": "shapegroup", "id": "lamp", "shapes": [{"type": "quad", "material": "light", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}]}])",
         "/shapes/0: shape group 'lamp' holds an emitter (material 'light')"},
        {"sphere in a group",
         R"([{"type": "shapegroup", "id": "g", "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}]}])",
         "/shapes/0/shapes/0/type: a shape group holds triangles, quads and meshes, not 'sphere'"},
        {"nested group",
         "[{\"type\": \"shapegroup\", \"id\": \"outer\", \"shapes\": [" + kGroup + "]}]",
         "/shapes/0/shapes/0/type: a shape group holds triangles, quads and meshes, not "
         "'shapegroup'"},
        {"duplicate id", "[" + kGroup + ", " + kGroup + "]",
         "/shapes/1/id: a second shape group 'tile'"},
        {"empty group", R"([{"type": "shapegroup", "id": "g", "shapes": []}])",
         "/shapes/0/shapes: expected a non-empty array of shapes"},
        {"singular to_world",
         "[" + kGroup +
             R"(, {"type": "instance", "shapegroup": "tile", "to_world": [{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1]]}]}])",
         "/shapes/1/to_world"},
        {"unknown key",
         "[" + kGroup + R"(, {"type": "instance", "shapegroup": "tile", "material": "white"}])",
         "/shapes/1"},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        const std::string message = error_of(with_shapes(c.shapes));
        CHECK(message.find("test.json: " + c.fragment) != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("instances: validate_scene refuses a NaN or singular to_world and a bad group index",
          "[scene][instances][errors]") {
    wp::Scene base = wp::parse_scene(
        with_shapes("[" + kGroup + R"(, {"type": "instance", "shapegroup": "tile"}])"),
        "test.json");
    wp::validate_scene(base);
    auto error = [](const wp::Scene& s) {
        try {
            wp::validate_scene(s);
        } catch (const wp::SceneError& e) {
            return std::string(e.what());
        }
        return std::string("<no error>");
    };
    wp::Scene nan = base;
    nan.instances[0].to_world[1][2] = std::numeric_limits<double>::quiet_NaN();
    CHECK(error(nan) == "test.json: instances[0].to_world: the instance's to_world has a "
                        "non-finite entry");
    wp::Scene singular = base;
    singular.instances[0].to_world[2] = glm::dvec4(0.0);
    CHECK(error(singular).find("test.json: instances[0].to_world: the instance's to_world is "
                               "singular") == 0);
    wp::Scene sheared = base; // not affine
    sheared.instances[0].to_world[0][3] = 0.5;
    CHECK(error(sheared).find("is not affine") != std::string::npos);
    wp::Scene bad_group = base;
    bad_group.instances[0].group = 3;
    CHECK(error(bad_group).find("test.json: instances[0].group: shape group index 3 out of "
                                "range (1 groups)") == 0);
}
