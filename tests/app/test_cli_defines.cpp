// -D name=value: a Mitsuba XML scene's $names from the command line, as
// Mitsuba's own -D gives them (docs/mitsuba-import.md).
#include "app/cli_run.hpp"

using namespace wp::test::cli;

namespace {

std::string quoted(const fs::path& path) {
    std::string text = "'";
    text += path.string();
    text += "'";
    return text;
}

// A scene whose light and size come from <default>s.
const char* const kScene = R"(<scene version="3.0.0">
    <default name="radiance" value="10"/>
    <default name="width" value="8"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="$width"/><integer name="height" value="8"/></film>
    </sensor>
    <shape type="rectangle">
        <emitter type="area"><rgb name="radiance" value="$radiance"/></emitter>
    </shape>
</scene>
)";

} // namespace

TEST_CASE("cli: -D sets a Mitsuba scene's $names over its <default>s", "[app][cli][mitsuba]") {
    Scratch s;
    const fs::path scene = s.write("lit.xml", kScene);
    // The default's value, then two others: the image's size and the light's
    // radiance (the rectangle fills the view, so every pixel is its radiance)
    // follow -D.
    Run plain = wavepath("info " + quoted(scene), s);
    INFO(plain.err);
    REQUIRE(plain.exit_code == 0);
    CHECK(plain.out.find("camera: 8x8") != std::string::npos);
    Run wide = wavepath("info " + quoted(scene) + " -D width=12 --define radiance=3", s);
    INFO(wide.err);
    REQUIRE(wide.exit_code == 0);
    CHECK(wide.out.find("camera: 12x8") != std::string::npos);

    // A value the parameter cannot take is the scene's error, naming $radiance's place.
    check_one_line_error(
        wavepath("render " + quoted(scene) + " -D radiance=bright --out " + quoted(s.dir / "x.exr"),
                 s),
        "value=\"$radiance\"");
    CHECK_FALSE(fs::exists(s.dir / "x.exr"));
    // Not name=value; and a JSON scene, which has no $names.
    check_one_line_error(wavepath("render " + quoted(scene) + " -D radiance", s),
                         "expected name=value");
    check_one_line_error(
        wavepath("render " + kHexroom + " -D radiance=3 --out " + quoted(s.dir / "x.exr"), s),
        "is a JSON scene, which has no $names to set");
}
