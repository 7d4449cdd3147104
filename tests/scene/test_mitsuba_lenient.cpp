// --lenient (SceneReadOptions::lenient, docs/mitsuba-import.md): a BSDF the
// reader refuses becomes a grey diffuse, and shapes, top-level emitters and
// integrators of plugins wavepath has not are left out, each with one
// warning naming its place; everything else stays an error, and without
// --lenient the same scenes are refused as before.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "scene/load.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kHead = R"(<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
)";

fs::path write(const wp::test::TempDir& dir, const std::string& body) {
    const fs::path path = dir / "s.xml";
    std::ofstream(path) << kHead << body << "</scene>\n";
    return path;
}

wp::Scene lenient(const fs::path& path) {
    wp::SceneReadOptions options;
    options.lenient = true;
    return wp::load_scene(path, options);
}

std::string strict_error(const fs::path& path) {
    try {
        (void)wp::load_scene(path);
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

std::string lenient_error(const fs::path& path) {
    try {
        (void)lenient(path);
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

// The warnings that mention --lenient.
std::vector<std::string> lenient_warnings(const wp::Scene& scene) {
    std::vector<std::string> out;
    for (const std::string& w : scene.warnings)
        if (w.find("--lenient") != std::string::npos)
            out.push_back(w);
    return out;
}

bool is_grey_diffuse(const wp::Material& m) {
    return m.kind == wp::MaterialKind::Diffuse && m.reflectance == glm::dvec3(0.5) &&
           !m.is_textured();
}

} // namespace

TEST_CASE("mitsuba lenient: a BSDF wavepath cannot read becomes a grey diffuse, one warning each",
          "[scene][mitsuba][lenient]") {
    wp::test::TempDir dir;
    const fs::path path = write(dir, R"(    <bsdf type="hair" id="fur"/>
    <shape type="rectangle"><ref id="fur"/></shape>
    <shape type="rectangle"><ref id="fur"/><transform name="to_world"><translate z="-1"/></transform></shape>
    <shape type="rectangle"><bsdf type="diffuse"><float name="roughness" value="0.3"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="twosided"><bsdf type="roughdiffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="conductor"><rgb name="specular_reflectance" value="2"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse">
        <texture type="checkerboard" name="reflectance"/>
        <float name="sheen" value="1"/>
    </bsdf></shape>
    <shape type="rectangle">
        <bsdf type="hair"/>
        <emitter type="area"><rgb name="radiance" value="3"/></emitter>
    </shape>
)");
    // Strict, as before: the first one is refused.
    CHECK(strict_error(path) == path.string() +
                                    ":6:5: <bsdf type=\"hair\" id=\"fur\">: unsupported BSDF type "
                                    "'hair' (wavepath reads diffuse, conductor, roughconductor, "
                                    "dielectric, thindielectric, roughdielectric, plastic, "
                                    "roughplastic and twosided)");

    const wp::Scene scene = lenient(path);
    REQUIRE(scene.triangles.size() == 14);
    // Every shape's material is the grey diffuse, the last one emitting as written.
    for (std::size_t t = 0; t < 12; ++t) {
        INFO("triangle " << t);
        const wp::Material& m = scene.materials[scene.triangles[t].material];
        CHECK(is_grey_diffuse(m));
        CHECK(m.emission == glm::dvec3(0.0));
    }
    const wp::Material& light = scene.materials[scene.triangles[12].material];
    CHECK(is_grey_diffuse(light));
    CHECK(light.emission == glm::dvec3(3.0));
    // The checkerboard of the failed BSDF is dropped with it.
    CHECK(scene.textures.empty());
    // The BSDF shared by two shapes is one material, named by its id.
    CHECK(scene.triangles[0].material == scene.triangles[2].material);
    CHECK(scene.materials[scene.triangles[0].material].name == "fur");

    const std::string f = path.string();
    const std::string replaced =
        ": replaced by a grey diffuse (reflectance 0.5), as --lenient asks: ";
    const std::vector<std::string> want = {
        f + ":6:5: <bsdf type=\"hair\" id=\"fur\">" + replaced +
            "unsupported BSDF type 'hair' (wavepath reads diffuse, conductor, roughconductor, "
            "dielectric, thindielectric, roughdielectric, plastic, roughplastic and twosided)",
        f + ":9:29: <bsdf type=\"diffuse\">" + replaced + f +
            ":9:50: <float name=\"roughness\">: wavepath does not support the parameter "
            "'roughness' of <bsdf type=\"diffuse\"> (it reads reflectance)",
        f + ":10:29: <bsdf type=\"twosided\">" + replaced + f +
            ":10:51: <bsdf type=\"roughdiffuse\">: unsupported BSDF type 'roughdiffuse' "
            "(wavepath reads diffuse, conductor, roughconductor, dielectric, thindielectric, "
            "roughdielectric, plastic, roughplastic and twosided)",
        f + ":11:29: <bsdf type=\"conductor\">" + replaced + f +
            ":11:52: <rgb name=\"specular_reflectance\">: must be in [0, 1], got 2",
        f + ":12:29: <bsdf type=\"diffuse\">" + replaced + f +
            ":14:9: <float name=\"sheen\">: wavepath does not support the parameter 'sheen' of "
            "<bsdf type=\"diffuse\"> (it reads none)",
        f + ":17:9: <bsdf type=\"hair\">" + replaced +
            "unsupported BSDF type 'hair' (wavepath reads diffuse, conductor, roughconductor, "
            "dielectric, thindielectric, roughdielectric, plastic, roughplastic and twosided)",
    };
    CHECK(lenient_warnings(scene) == want);
}

TEST_CASE("mitsuba lenient: shapes, emitters and integrators of other plugins are left out",
          "[scene][mitsuba][lenient]") {
    wp::test::TempDir dir;
    const fs::path path = write(
        dir, R"(    <integrator type="volpath"><integer name="max_depth" value="8"/></integrator>
    <emitter type="sunsky"><float name="turbidity" value="3"/></emitter>
    <shape type="cylinder"><float name="radius" value="0.3"/></shape>
    <shape type="rectangle"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
    <emitter type="point"><point name="position" value="0, 0, 3"/></emitter>
)");
    CHECK(strict_error(path) ==
          path.string() +
              ":6:5: <integrator type=\"volpath\">: unsupported integrator 'volpath' (wavepath "
              "renders with Mitsuba's path integrator; --lenient renders the scene with it)");
    const wp::Scene scene = lenient(path);
    CHECK(scene.triangles.size() == 2);
    REQUIRE(scene.emitters.size() == 1);
    CHECK(scene.emitters[0].kind == wp::EmitterKind::Point);
    const std::string f = path.string();
    const std::vector<std::string> want = {
        f + ":6:5: <integrator type=\"volpath\">: left out: wavepath renders with its path "
            "tracer (Mitsuba's path) and that integrator's defaults (--lenient)",
        f + ":7:5: <emitter type=\"sunsky\">: left out: wavepath has no 'sunsky' emitter "
            "(--lenient)",
        f + ":8:5: <shape type=\"cylinder\">: left out: wavepath has no 'cylinder' shape "
            "(--lenient)",
    };
    CHECK(lenient_warnings(scene) == want);
}

TEST_CASE("mitsuba lenient: what is not an unsupported plugin stays an error",
          "[scene][mitsuba][lenient]") {
    wp::test::TempDir dir;
    // A missing mesh file, a supported shape's unknown parameter, a supported
    // emitter's bad value, an unsupported sensor, and a scene with nothing
    // left to render.
    CHECK(lenient_error(
              write(dir, R"(<shape type="ply"><string name="filename" value="gone.ply"/></shape>
)"))
              .find("gone.ply: cannot open mesh file") != std::string::npos);
    CHECK(lenient_error(write(dir, R"(<shape type="cube"><float name="radius" value="1"/></shape>
)"))
              .find("wavepath does not support the parameter 'radius' of <shape "
                    "type=\"cube\">") != std::string::npos);
    CHECK(lenient_error(
              write(dir, R"(<emitter type="point"><float name="intensity" value="-1"/></emitter>
    <shape type="cube"/>
)"))
              .find("<float name=\"intensity\">: must be in") != std::string::npos);
    CHECK(lenient_error(write(dir, R"(<shape type="cylinder"/>
)"))
              .find("the scene has no shapes") != std::string::npos);
    // A JSON scene is read strictly: --lenient is refused, as -D is.
    const fs::path json = dir / "s.json";
    std::ofstream(json) << "{}";
    CHECK(lenient_error(json) == "--lenient: '" + json.string() +
                                     "' is a JSON scene, which wavepath reads strictly "
                                     "(--lenient is for Mitsuba XML scenes)");
}
