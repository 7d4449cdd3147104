// Emitting spheres as the scene files give them: a sphere of an emissive
// material in JSON, a sphere with an `area` emitter in Mitsuba XML, and the
// export's round trip of it.
#include <catch2/catch.hpp>

#include <string>

#include "scene/load.hpp"
#include "scene/mitsuba/load_mitsuba.hpp"
#include "scene/mitsuba_export.hpp"
#include "support/scene_json.hpp"
#include "support/temp_dir.hpp"

TEST_CASE("loader: a sphere of an emissive material is a sphere light", "[scene][load]") {
    const wp::Scene s = wp::parse_scene(
        wp::test::scene_json(wp::test::kSceneCamera, wp::test::kSceneMaterials,
                             R"([{"type": "sphere", "center": [0, 0, 2], "radius": 0.5,
                                  "material": "light"}])"),
        "test.json");
    REQUIRE(s.spheres.size() == 1);
    CHECK(s.materials[s.spheres[0].material].emission == glm::dvec3(100.0));
    CHECK(wp::has_sphere_lights(s));
    CHECK(wp::has_lights_besides_triangles(s));
}

TEST_CASE("Mitsuba reader: a sphere with an area emitter, and back through the export",
          "[scene][mitsuba]") {
    wp::test::TempDir dir;
    wp::test::write_text(dir / "s.xml", R"(<scene version="3.0.0">
        <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
        <integer name="height" value="8"/></film></sensor>
        <shape type="rectangle"/>
        <shape type="sphere"><point name="center" x="0" y="1" z="2"/><float name="radius" value="0.25"/>
            <emitter type="area"><rgb name="radiance" value="3, 4, 5"/></emitter></shape>
        </scene>)");
    const wp::Scene s = wp::load_mitsuba_scene(dir / "s.xml");
    REQUIRE(s.spheres.size() == 1);
    CHECK(s.spheres[0].radius == 0.25);
    CHECK(s.materials[s.spheres[0].material].emission == glm::dvec3(3, 4, 5));
    // The export writes the emitter inside the sphere's shape again.
    const wp::MitsubaExport exported = wp::export_mitsuba(s, "s");
    CHECK(exported.xml.find("<shape type=\"sphere\">") != std::string::npos);
    CHECK(exported.xml.find("<emitter type=\"area\">") != std::string::npos);
}
