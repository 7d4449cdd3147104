// A Mitsuba file's max_depth, and --max-depth with a Mitsuba file: both are
// Mitsuba's max_depth, the longest path in edges, the camera ray included
// (docs/mitsuba-import.md, "max_depth"); the command line's wins.
#include <cmath>
#include <string>

#include "app/cli_run.hpp"
#include "image/exr.hpp"

using namespace wp::test::cli;

namespace {

// max-depth.xml: a light of radiance 12 that the camera sees, a lit floor,
// a box filter; its max_depth is 2 unless -D says otherwise.
const std::string kScene =
    std::string("'") + WAVEPATH_SOURCE_DIR + "/tests/data/mitsuba/max-depth.xml'";

// Renders at 4 spp with `options`; the image, or an empty one on failure.
wp::Image render(const Scratch& s, const std::string& options) {
    const fs::path out = s.dir / "out.exr";
    fs::remove(out);
    const Run run = wavepath("render " + kScene + " --spp 4 --seed 2 --quiet --out '" +
                                 out.string() + "' " + options,
                             s);
    INFO(options << ": " << run.err);
    REQUIRE(run.exit_code == 0);
    return wp::read_exr(out);
}

// Whether every value is the light's 12 times a whole number of the 4
// samples: the emitters the camera sees, and nothing else.
bool emission_only(const wp::Image& image) {
    for (float v : image.rgb)
        if (v * 4.0 / 12.0 != std::round(v * 4.0 / 12.0))
            return false;
    return true;
}

} // namespace

TEST_CASE("cli: --max-depth with a Mitsuba scene is Mitsuba's max_depth, over the file's",
          "[app][cli][mitsuba]") {
    Scratch s;
    const wp::Image file = render(s, "");                             // the file's 2: direct light
    const wp::Image one = render(s, "--max-depth 1");                 // Mitsuba's 1
    const wp::Image defined = render(s, "-D max_depth=1");            // the file's, set to 1
    const wp::Image both = render(s, "-D max_depth=3 --max-depth 1"); // the command line wins
    CHECK_FALSE(emission_only(file));
    CHECK(emission_only(one));
    CHECK(one.rgb == defined.rgb);
    CHECK(one.rgb == both.rgb);
}

TEST_CASE("cli: a bad max_depth in a Mitsuba file is one line with its place",
          "[app][cli][mitsuba][errors]") {
    Scratch s;
    const fs::path out = s.dir / "out.exr";
    for (const char* value : {"0", "-2", "1.5"}) {
        INFO("max_depth " << value);
        const Run run = wavepath("render " + kScene + " --spp 1 --quiet --out '" + out.string() +
                                     "' -D max_depth=" + value,
                                 s);
        check_one_line_error(run, "max-depth.xml:");
        CHECK(run.err.find("max_depth") != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    }
}
