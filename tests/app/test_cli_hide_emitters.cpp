// hide_emitters of Mitsuba's path integrator: what the camera sees of an
// emitter directly is black, and the light it casts is unchanged
// (docs/mitsuba-import.md).
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

// The left half of the view is a light of radiance 3 facing the camera; the
// right half a grey diffuse plane, lit by a uniform sky of radiance 1 that
// the light does not reach (it faces the camera, away from the plane).
std::string scene(bool hide) {
    return std::string(R"(<scene version="3.0.0">
    <integrator type="path"><boolean name="hide_emitters" value=")") +
           (hide ? "true" : "false") + R"("/></integrator>
    <sensor type="perspective">
        <float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>
            <rfilter type="box"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
    <shape type="rectangle">
        <transform name="to_world"><scale x="500" y="1000"/><translate x="500"/></transform>
        <emitter type="area"><rgb name="radiance" value="3"/></emitter>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale x="500" y="1000"/><translate x="-500"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"/></bsdf>
    </shape>
</scene>
)";
}

// The mean of the columns [x0, x1) of the image's first channel.
double column_mean(const wp::Image& image, int x0, int x1) {
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = x0; x < x1; ++x)
            sum += image.pixel(x, y)[0];
    return sum / (image.height * (x1 - x0));
}

} // namespace

TEST_CASE("cli: hide_emitters blacks out the lights the camera sees, not their light",
          "[app][cli][mitsuba]") {
    Scratch s;
    for (bool hide : {false, true}) {
        INFO("hide_emitters " << hide);
        const fs::path xml = s.write(hide ? "hidden.xml" : "shown.xml", scene(hide));
        const fs::path out = s.dir / "out.exr";
        const Run run =
            wavepath("render " + quoted(xml) + " --spp 32 --quiet --out " + quoted(out), s);
        INFO(run.err);
        REQUIRE(run.exit_code == 0);
        const wp::Image image = wp::read_exr(out);
        REQUIRE(image.width == 8);
        // The light at world x > 0 fills columns 4-7 (the camera looks down
        // -z, +y up, so world +x is the image's right), the plane columns 0-3.
        CHECK(column_mean(image, 4, 8) == Approx(hide ? 0.0 : 3.0).margin(1e-6));
        // The grey plane under the sky (the light faces away from it): 0.5.
        CHECK(column_mean(image, 0, 4) == Approx(0.5).epsilon(0.03));
    }
}
