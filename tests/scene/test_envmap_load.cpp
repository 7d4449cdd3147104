// The envmap emitter as the scene files give it: the JSON loader's and the
// Mitsuba XML reader's, Mitsuba's defaults, and every bad input, each a
// one-line error that names the field (and the file).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "scene/load.hpp"
#include "scene/mitsuba/load_mitsuba.hpp"
#include "support/scene_json.hpp"
#include "support/temp_dir.hpp"

namespace {

const std::filesystem::path kTextures =
    std::filesystem::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "mitsuba" / "textures";

std::string scene_with_emitters(const std::string& emitters) {
    std::string json = wp::test::scene_json();
    json.pop_back(); // the closing brace
    return json + R"(, "emitters": )" + emitters + "}";
}

wp::Scene parse_in(const std::filesystem::path& folder, const std::string& json) {
    return wp::parse_scene(json, (folder / "test.json").string());
}

std::string error_in(const std::filesystem::path& folder, const std::string& json) {
    try {
        (void)parse_in(folder, json);
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

} // namespace

TEST_CASE("loader: an envmap emitter in a JSON scene", "[scene][load][envmap]") {
    const wp::Scene s = parse_in(kTextures, scene_with_emitters(R"([{"type": "envmap",
        "filename": "sky.exr", "scale": 2.5, "to_world": [{"rotate": {"angle": 90,
        "axis": [0, 1, 0]}}]}])"));
    REQUIRE(s.emitters.size() == 1);
    const wp::Emitter& e = s.emitters[0];
    CHECK(e.kind == wp::EmitterKind::Envmap);
    CHECK(e.value == glm::dvec3(2.5));
    REQUIRE(e.image);
    CHECK(e.image->width == 64);
    CHECK(e.image->height == 32);
    CHECK(e.image->encoding == wp::TexelEncoding::Float32);
    // A quarter turn about +y takes +x to -z.
    const glm::dvec3 x = e.to_world * glm::dvec3(1, 0, 0);
    CHECK(std::abs(x.x) < 1e-15);
    CHECK(x.z == Approx(-1.0));
    CHECK(s.files.back() == (kTextures / "sky.exr").string());
    // Mitsuba's defaults: scale 1, no rotation.
    const wp::Scene plain =
        parse_in(kTextures, scene_with_emitters(R"([{"type": "envmap", "filename": "sky.exr"}])"));
    CHECK(plain.emitters[0].value == glm::dvec3(1.0));
    CHECK(plain.emitters[0].to_world == glm::dmat3(1.0));
}

TEST_CASE("loader: bad envmaps are one-line errors naming the field and the file",
          "[scene][load][envmap]") {
    auto error = [](const std::string& emitters) {
        return error_in(kTextures, scene_with_emitters(emitters));
    };
    CHECK(error(R"([{"type": "envmap"}])")
              .find("/emitters/0/filename: missing required field 'filename'") !=
          std::string::npos);
    CHECK(error(R"([{"type": "envmap", "filename": "gone.exr"}])").find("gone.exr") !=
          std::string::npos);
    CHECK(error(R"([{"type": "envmap", "filename": "sky.exr", "scale": -1}])")
              .find("/emitters/0/scale: must be in [0, ") != std::string::npos);
    CHECK(error(R"([{"type": "envmap", "filename": "sky.exr", "to_world": [{"scale": 2}]}])")
              .find("/emitters/0/to_world: must be a rotation") != std::string::npos);
    CHECK(
        error(R"([{"type": "envmap", "filename": "sky.exr", "to_world": [{"scale": [1, -1, 1]}]}])")
            .find("/emitters/0/to_world: must be a rotation") != std::string::npos);
    CHECK(error(R"([{"type": "envmap", "filename": "sky.exr", "bitmap": 1}])").find("bitmap") !=
          std::string::npos);
    CHECK(error(R"([{"type": "constant", "radiance": [1, 1, 1]},
                    {"type": "envmap", "filename": "sky.exr"}])")
              .find("/emitters/1: a second environment") != std::string::npos);
    // A file that is not an image.
    wp::test::TempDir dir;
    wp::test::write_text(dir / "sky.exr", "not an image");
    const std::string corrupt =
        error_in(dir.path(), scene_with_emitters(R"([{"type": "envmap", "filename": "sky.exr"}])"));
    CHECK(corrupt.find("/emitters/0/filename") != std::string::npos);
    CHECK(corrupt.find("sky.exr") != std::string::npos);
    CHECK(corrupt.find('\n') == std::string::npos);
}

TEST_CASE("Mitsuba reader: an envmap emitter, and bad ones", "[scene][mitsuba][envmap]") {
    wp::test::TempDir dir;
    std::filesystem::copy_file(kTextures / "sky.exr", dir / "sky.exr");
    auto load = [&](const std::string& emitter) {
        wp::test::write_text(dir / "s.xml", R"(<scene version="3.0.0">
        <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
        <integer name="height" value="8"/></film></sensor>
        <shape type="sphere"/>
        )" + emitter + "</scene>");
        return wp::load_mitsuba_scene(dir / "s.xml");
    };
    const wp::Scene s = load(R"(<emitter type="envmap">
        <string name="filename" value="sky.exr"/><float name="scale" value="0.5"/>
        <boolean name="mis_compensation" value="true"/>
        <transform name="to_world"><rotate y="1" angle="-90"/></transform></emitter>)");
    REQUIRE(s.emitters.size() == 1);
    CHECK(s.emitters[0].kind == wp::EmitterKind::Envmap);
    CHECK(s.emitters[0].value == glm::dvec3(0.5));
    CHECK((s.emitters[0].to_world * glm::dvec3(1, 0, 0)).z == Approx(1.0));
    CHECK(s.files.back() == (dir / "sky.exr").string());

    auto error = [&](const std::string& emitter) {
        try {
            (void)load(emitter);
        } catch (const wp::SceneError& e) {
            return std::string(e.what());
        }
        return std::string("<no error>");
    };
    CHECK(error(R"(<emitter type="envmap"/>)").find("needs its filename") != std::string::npos);
    CHECK(error(R"(<emitter type="envmap"><string name="filename" value="gone.hdr"/></emitter>)")
              .find("gone.hdr") != std::string::npos);
    CHECK(error(R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
        <transform name="to_world"><scale value="2"/></transform></emitter>)")
              .find("must be a rotation") != std::string::npos);
    CHECK(error(R"(<emitter type="constant"/><emitter type="envmap">
        <string name="filename" value="sky.exr"/></emitter>)")
              .find("a second environment") != std::string::npos);
}
