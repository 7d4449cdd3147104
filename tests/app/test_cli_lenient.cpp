// --lenient on every command that loads a scene: a Mitsuba scene with a BSDF
// wavepath cannot read renders with a grey diffuse in its place and one
// warning naming the element; without it the scene is refused as before
// (docs/mitsuba-import.md, "--lenient").
#include <numeric>

#include "app/cli_run.hpp"
#include "image/exr.hpp"

using namespace wp::test::cli;

namespace {

std::string quoted(const fs::path& path) {
    // Built up in steps: "'" + path.string() + "'" trips GCC 12's -Wrestrict.
    std::string text = "'";
    text += path.string();
    text += "'";
    return text;
}

// A plane filling the view under a uniform sky of radiance 1: a grey
// diffuse 0.5 there reflects 0.5 (it sees the sky and nothing else).
const char* const kScene = R"(<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
    <shape type="rectangle">
        <transform name="to_world"><scale value="1000"/></transform>
        <bsdf type="hair"><float name="eumelanin" value="1.3"/></bsdf>
    </shape>
</scene>
)";

const char* const kWarning = ":10:9: <bsdf type=\"hair\">: replaced by a grey diffuse (reflectance "
                             "0.5), as --lenient asks: unsupported BSDF type 'hair'";

} // namespace

TEST_CASE("cli: --lenient renders an unsupported BSDF as a grey diffuse, with a warning",
          "[app][cli][mitsuba]") {
    Scratch s;
    const fs::path scene = s.write("hair.xml", kScene);
    const fs::path out = s.dir / "hair.exr";

    // As before without --lenient: one line, nothing written.
    check_one_line_error(wavepath("render " + quoted(scene) + " --spp 4 --out " + quoted(out), s),
                         "hair.xml:10:9: <bsdf type=\"hair\">: unsupported BSDF type 'hair'");
    CHECK_FALSE(fs::exists(out));

    const Run run =
        wavepath("render " + quoted(scene) + " --lenient --spp 16 --quiet --out " + quoted(out), s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.find("wavepath: warning: " + scene.string() + kWarning) != std::string::npos);
    const wp::Image image = wp::read_exr(out);
    REQUIRE(image.rgb.size() == 8 * 8 * 3);
    const double mean = std::accumulate(image.rgb.begin(), image.rgb.end(), 0.0) /
                        static_cast<double>(image.rgb.size());
    CHECK(mean == Approx(0.5).epsilon(0.02));

    // Every other command that loads a scene takes it too.
    for (const std::string command : {"info", "converge", "bench", "breakdown", "export-mitsuba"}) {
        INFO(command);
        const Run help = wavepath(command + " --help", s);
        CHECK(help.out.find("--lenient") != std::string::npos);
    }
    const Run info = wavepath("info " + quoted(scene) + " --lenient", s);
    CHECK(info.exit_code == 0);
    CHECK(info.out.find("  warning: " + scene.string() + kWarning) != std::string::npos);
    // The export writes what was rendered: the grey diffuse.
    const fs::path exported = s.dir / "grey.xml";
    const Run exp =
        wavepath("export-mitsuba " + quoted(scene) + " " + quoted(exported) + " --lenient", s);
    INFO(exp.err);
    REQUIRE(exp.exit_code == 0);
    const std::string xml = slurp(exported);
    CHECK(xml.find("type=\"hair\"") == std::string::npos);
    CHECK(xml.find("type=\"diffuse\"") != std::string::npos);

    // A JSON scene is read strictly: --lenient is refused, as -D is.
    check_one_line_error(
        wavepath("render " + kHexroom + " --lenient --out " + quoted(s.dir / "x.exr"), s),
        "is a JSON scene, which wavepath reads strictly");
}
