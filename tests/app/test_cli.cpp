// The wavepath executable, run as a user would: bad input gets one clear line
// on stderr and a non-zero exit, and never a crash or a half-written file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "image/image_io.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
    int exit_code = -1;
    std::string out;
    std::string err;
};

std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// A scratch directory per test case, removed at the end.
struct Scratch {
    fs::path dir;
    Scratch() {
        dir = fs::temp_directory_path() / ("wavepath-cli-" + std::to_string(::getpid()) + "-" +
                                           std::to_string(std::hash<std::string>{}(
                                               Catch::getResultCapture().getCurrentTestName())));
        fs::create_directories(dir);
    }
    ~Scratch() { fs::remove_all(dir); }
    fs::path write(const std::string& name, const std::string& text) const {
        std::ofstream(dir / name) << text;
        return dir / name;
    }
};

Run wavepath(const std::string& arguments, const Scratch& scratch) {
    fs::path out = scratch.dir / "stdout.txt", err = scratch.dir / "stderr.txt";
    std::string command = std::string("'") + WAVEPATH_EXE + "' " + arguments + " >'" +
                          out.string() + "' 2>'" + err.string() + "'";
    int status = std::system(command.c_str());
    Run run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.out = slurp(out);
    run.err = slurp(err);
    fs::remove(out);
    fs::remove(err);
    return run;
}

// One line, starting "wavepath: error:", that mentions `what`.
void check_one_line_error(const Run& run, const std::string& what) {
    INFO("stderr: " << run.err);
    CHECK(run.exit_code != 0);
    CHECK(run.exit_code < 128); // not killed by a signal
    CHECK(run.err.rfind("wavepath: error: ", 0) == 0);
    CHECK(run.err.find(what) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

const std::string kHexroom = std::string("'") + WAVEPATH_SOURCE_DIR + "/scenes/hexroom.json'";

} // namespace

TEST_CASE("cli: devices lists the PoCL CPU device") {
    Scratch s;
    Run run = wavepath("devices", s);
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("0:0") != std::string::npos);
    CHECK(run.out.find("CPU") != std::string::npos);
    CHECK(run.out.find("compute units") != std::string::npos);
}

TEST_CASE("cli: a small render writes readable HDR and PNG files") {
    Scratch s;
    fs::path pfm = s.dir / "out.pfm", png = s.dir / "out.png";
    Run run =
        wavepath("render " + kHexroom + " --spp 2 --width 12 --height 10 --device 0:0 --out '" +
                     pfm.string() + "' --png '" + png.string() + "'",
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
    SECTION("more pixels than the device can hold") {
        check_one_line_error(wavepath("render " + kHexroom +
                                          " --width 16384 --height 16384 --out '" + out.string() +
                                          "'",
                                      s),
                             "out of device memory");
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
