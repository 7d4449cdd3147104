// The wavepath executable, run as a user would: bad input gets one clear line
// on stderr and a non-zero exit, and never a crash or a half-written file.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "app/cli_run.hpp"
#include "image/image_io.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

TEST_CASE("cli: devices lists the test device") {
    Scratch s;
    Run run = wavepath("devices", s);
    CHECK(run.exit_code == 0);
    const wp::DeviceInfo device = wp::test::device_info();
    CHECK(run.out.find(device.index_string() + "  " + device.name) != std::string::npos);
    CHECK(run.out.find("type: " + device.type) != std::string::npos);
    CHECK(run.out.find("compute units") != std::string::npos);
}

TEST_CASE("cli: WAVEPATH_DEVICE picks the device when --device is absent") {
    Scratch s;
    const std::string to =
        " --spp 1 --width 4 --height 4 --out '" + (s.dir / "x.pfm").string() + "'";
    Run run = wavepath("render " + kHexroom + to, s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.find(" on " + wp::test::device_info().name + " ") != std::string::npos);
    Run wrong = wavepath("render " + kHexroom + to, s, "WAVEPATH_DEVICE=no-such-device");
    check_one_line_error(wrong, "'no-such-device' (from WAVEPATH_DEVICE)");
}

TEST_CASE("cli: a small render writes readable HDR and PNG files") {
    Scratch s;
    fs::path pfm = s.dir / "out.pfm", png = s.dir / "out.png";
    Run run = wavepath("render " + kHexroom + " --spp 2 --width 12 --height 10 --device " +
                           test_device_index() + " --out '" + pfm.string() + "' --png '" +
                           png.string() + "'",
                       s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    wp::Image image = wp::read_image(pfm);
    CHECK(image.width == 12);
    CHECK(image.height == 10);
    CHECK(fs::file_size(png) > 0);
    CHECK(run.out.find("NaN/Inf samples dropped: 0") != std::string::npos);
    // Nothing but the two images is left behind (no temporary files).
    int files = 0;
    for (const auto& entry : fs::directory_iterator(s.dir))
        files += entry.is_regular_file();
    CHECK(files == 2);
}

TEST_CASE("cli: bad input gives one clear line and a non-zero exit") {
    Scratch s;
    fs::path out = s.dir / "never.exr";
    const std::string to = " --spp 1 --width 8 --height 8 --out '" + out.string() + "'";

    SECTION("missing scene file") {
        check_one_line_error(wavepath("render '" + (s.dir / "missing.json").string() + "'" + to, s),
                             "missing.json");
    }
    SECTION("malformed JSON") {
        fs::path bad = s.write("bad.json", "{\"camera\": [1, 2,");
        check_one_line_error(wavepath("render '" + bad.string() + "'" + to, s), "bad.json");
    }
    SECTION("a number float32 cannot carry") {
        std::string scene = slurp(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
        scene.replace(scene.find("\"radius\": 2"), 11, "\"radius\": 1e999");
        fs::path bad = s.write("huge.json", scene);
        check_one_line_error(wavepath("render '" + bad.string() + "'" + to, s), "radius");
    }
    SECTION("negative radius") {
        std::string scene = slurp(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
        scene.replace(scene.find("\"radius\": 2"), 11, "\"radius\": -2");
        fs::path bad = s.write("negative.json", scene);
        check_one_line_error(wavepath("render '" + bad.string() + "'" + to, s), "radius");
    }
    SECTION("unknown device") {
        Run run = wavepath("render " + kHexroom + to + " --device no-such-device", s);
        check_one_line_error(run, "no-such-device");
        CHECK(run.err.find("0:0") != std::string::npos); // lists what exists
        check_one_line_error(wavepath("render " + kHexroom + to + " --device 7:3", s), "7:3");
    }
    SECTION("zero resolution") {
        check_one_line_error(
            wavepath("render " + kHexroom + " --width 0 --out '" + out.string() + "'", s),
            "--width");
    }
    SECTION("unsupported output format") {
        check_one_line_error(
            wavepath("render " + kHexroom + " --spp 1 --out '" + (s.dir / "x.bmp").string() + "'",
                     s),
            ".bmp");
    }
    SECTION("output directory missing") {
        check_one_line_error(wavepath("render " + kHexroom + " --spp 1 --out '" +
                                          (s.dir / "no" / "x.exr").string() + "'",
                                      s),
                             "does not exist");
    }
    SECTION("shade sorted by material with a fused launch plan") {
        check_one_line_error(
            wavepath("render " + kHexroom + to + " --shade-order sorted --launch-plan wave", s),
            "--shade-order sorted needs the stages launch plan");
    }
    SECTION("more pixels than the device can hold") {
        check_one_line_error(wavepath("render " + kHexroom +
                                          " --width 16384 --height 16384 --out '" + out.string() +
                                          "'",
                                      s),
                             "out of device memory: a 16384x16384 image needs");
    }
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("cli: an existing output survives a failed render") {
    Scratch s;
    fs::path out = s.write("keep.exr", "previous contents");
    fs::path bad = s.write("bad.json", "{");
    Run run = wavepath("render '" + bad.string() + "' --out '" + out.string() + "'", s);
    CHECK(run.exit_code != 0);
    CHECK(slurp(out) == "previous contents");
}

TEST_CASE("cli: render takes the estimator flags and each changes the image but not its mean") {
    Scratch s;
    const std::string size =
        " --spp 16 --width 24 --height 24 --device " + test_device_index() + " --out ";
    auto render = [&](const std::string& name, const std::string& flags) {
        const fs::path path = s.dir / (name + ".pfm");
        Run run = wavepath("render " + kHexroom + size + "'" + path.string() + "'" + flags, s);
        INFO(run.err);
        REQUIRE(run.exit_code == 0);
        return wp::read_image(path);
    };
    const wp::Image standard = render("default", "");
    CHECK(render("again", "").rgb == standard.rgb); // so a difference below is the flag's
    for (const std::string flags :
         {" --no-nee", " --diffuse report", " --light-sampling solid-angle", " --seed 7"}) {
        INFO("flags:" << flags);
        const wp::Image other = render("other", flags);
        REQUIRE(other.rgb.size() == standard.rgb.size());
        CHECK(other.rgb != standard.rgb);
        // Both estimators are unbiased and independent, so every pixel's
        // difference has mean zero; its square estimates its variance, and
        // the mean difference must lie within 5 of its standard errors.
        for (std::size_t channel = 0; channel < 3; ++channel) {
            double sum = 0.0, sum_squares = 0.0, pixels = 0.0;
            for (std::size_t i = channel; i < standard.rgb.size(); i += 3) {
                const double d = static_cast<double>(other.rgb[i]) - standard.rgb[i];
                sum += d;
                sum_squares += d * d;
                pixels += 1.0;
            }
            INFO("channel " << channel);
            CHECK(sum_squares > 0.0);
            CHECK(std::abs(sum / pixels) <= 5.0 * std::sqrt(sum_squares) / pixels);
        }
    }
}

TEST_CASE("cli: --no-cache leaves the program cache directory alone") {
    Scratch s;
    const fs::path cache = s.dir / "cache";
    // PoCL's cache left to wavepath's choice, which is inside its own (the
    // tests otherwise share one for the whole run: tests/catch_main.cpp).
    const std::string environment = "WAVEPATH_CACHE_DIR='" + cache.string() + "' POCL_CACHE_DIR=";
    const std::string arguments = "render " + kHexroom + " --spp 1 --width 8 --height 8 --device " +
                                  test_device_index() + " --seed 11 --out '" +
                                  (s.dir / "x.pfm").string() + "'";
    Run off = wavepath(arguments + " --no-cache", s, environment);
    INFO(off.err);
    REQUIRE(off.exit_code == 0);
    CHECK_FALSE(fs::exists(cache));
    // The same render without the flag stores its kernels there (PoCL's
    // cache, app/caches.cpp), so the check above could fail.
    Run on = wavepath(arguments, s, environment);
    INFO(on.err);
    REQUIRE(on.exit_code == 0);
    REQUIRE(fs::is_directory(cache));
    CHECK_FALSE(fs::is_empty(cache));
}

namespace {

// A room (floor, back wall, light) around the unit cube of tests/data/meshes/cube.obj,
// copied to models/ beside the scene, so the mesh's relative path is resolved
// against the scene file.
std::string mesh_scene(bool with_mesh) {
    const std::string mesh = R"(,
        {"type": "mesh", "file": "models/cube.obj", "material": "red",
         "transform": [{"translate": [-0.5, -0.5, 0]}, {"rotate": {"angle": 30, "axis": [0, 0, 1]}}]})";
    return std::string(R"({
      "camera": {"eye": [-4, 0, 1.5], "look_at": [0, 0, 0.5], "up": [0, 0, 1], "fov": 40, "resolution": [16, 16]},
      "materials": {"white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
                    "red": {"type": "diffuse", "reflectance": [0.7, 0.1, 0.1]},
                    "light": {"type": "emitter", "radiance": [20, 20, 20]}},
      "shapes": [
        {"type": "quad", "material": "white", "vertices": [[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]]},
        {"type": "quad", "material": "white", "vertices": [[3, -5, 0], [3, -5, 5], [3, 5, 5], [3, 5, 0]]},
        {"type": "quad", "material": "light", "vertices": [[-1, -1, 4], [-1, 1, 4], [1, 1, 4], [1, -1, 4]]})") +
           (with_mesh ? mesh : "") + "]}";
}

} // namespace

TEST_CASE("cli: renders a scene with a mesh file") {
    Scratch s;
    fs::create_directories(s.dir / "models");
    fs::copy_file(fs::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "meshes" / "cube.obj",
                  s.dir / "models" / "cube.obj");
    auto render = [&](const std::string& name, bool with_mesh) {
        const fs::path scene = s.write(name + ".json", mesh_scene(with_mesh));
        const fs::path image = s.dir / (name + ".pfm");
        Run run = wavepath("render '" + scene.string() + "' --spp 4 --device 0:0 --out '" +
                               image.string() + "'",
                           s);
        INFO(run.err);
        REQUIRE(run.exit_code == 0);
        CHECK(run.out.find("NaN/Inf samples dropped: 0") != std::string::npos);
        return wp::read_image(image);
    };
    const wp::Image with = render("with-mesh", true);
    REQUIRE(with.width == 16);
    REQUIRE(with.height == 16);
    double sum = 0.0;
    for (const float v : with.rgb) {
        REQUIRE(std::isfinite(v));
        sum += v;
    }
    CHECK(sum > 0.0); // not black
    // The cube is seen: the same room without it gives another image.
    CHECK(render("without-mesh", false).rgb != with.rgb);
}

TEST_CASE("cli: a missing mesh file gives one line naming the scene's field") {
    Scratch s;
    const fs::path scene = s.write("scene.json", mesh_scene(true)); // no models/ folder
    Run run = wavepath(
        "render '" + scene.string() + "' --spp 1 --out '" + (s.dir / "x.pfm").string() + "'", s);
    check_one_line_error(run, "scene.json: /shapes/3/file: ");
    CHECK(run.err.find("cube.obj: cannot open mesh file") != std::string::npos);
    CHECK_FALSE(fs::exists(s.dir / "x.pfm"));
}

TEST_CASE("cli: the Cornell box has its red wall on the left and its green wall on the right") {
    Scratch s;
    const fs::path image = s.dir / "box.pfm";
    Run run = wavepath("render '" + std::string(WAVEPATH_SOURCE_DIR) +
                           "/scenes/cornell-box.json' --spp 16 --width 32 --height 32 --device "
                           "0:0 --out '" +
                           image.string() + "'",
                       s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    const wp::Image box = wp::read_image(image);
    // The walls fill the outer columns at mid height (the camera sees them
    // from x = 278 with a 39.3 degree field of view): sum red and green over
    // the two outermost columns on each side, rows 8 to 23.
    auto channel_sum = [&](int x0, int x1, int channel) {
        double sum = 0.0;
        for (int y = 8; y < 24; ++y)
            for (int x = x0; x < x1; ++x)
                sum += box.rgb[3 * (static_cast<std::size_t>(y) * 32 + x) + channel];
        return sum;
    };
    CHECK(channel_sum(0, 2, 0) > 2.0 * channel_sum(0, 2, 1));     // left: red
    CHECK(channel_sum(30, 32, 1) > 2.0 * channel_sum(30, 32, 0)); // right: green
}
