// Outputs are checked before any work: one that would overwrite an input or
// another output, and one that could not be written, are refused at once,
// and a value that would make the result meaningless is refused with them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "app/cli_run.hpp"
#include "image/image_io.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

// A 4x4 render of the hexroom with `flags`.
Run render(const std::string& flags, const Scratch& s) {
    return wavepath("render " + kHexroom + " --spp 1 --width 4 --height 4 " + flags, s);
}

std::string quoted(const fs::path& path) {
    std::string text = "'";
    return text.append(path.string()).append("'");
}

// A room around tests/data/meshes/<source>, copied beside the scene as `mesh`.
fs::path write_mesh_scene(const Scratch& s, const std::string& mesh,
                          const std::string& source = "cube.obj") {
    fs::copy_file(fs::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "meshes" / source,
                  s.dir / mesh);
    return s.write("mesh.json", R"({
      "camera": {"eye": [-4, 0, 1.5], "look_at": [0, 0, 0.5], "up": [0, 0, 1], "fov": 40, "resolution": [8, 8]},
      "materials": {"red": {"type": "diffuse", "reflectance": [0.7, 0.1, 0.1]},
                    "blue": {"type": "diffuse", "reflectance": [0.1, 0.1, 0.7]},
                    "light": {"type": "emitter", "radiance": [20, 20, 20]}},
      "shapes": [
        {"type": "quad", "material": "light", "vertices": [[-1, -1, 4], [-1, 1, 4], [1, 1, 4], [1, -1, 4]]},
        {"type": "mesh", "file": ")" +
                                    mesh + R"(", "material": "red"}]})");
}

// A character device node in the test's own directory with /dev/null's
// number (1:3) or /dev/zero's (1:5); false where this user may not make one.
bool make_char_device(const fs::path& path, unsigned minor) {
    return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)) == 0;
}

bool is_char_device(const fs::path& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

} // namespace

TEST_CASE("cli: an output that is one of the scene's mesh files is refused before any work") {
    Scratch s;
    const fs::path scene = write_mesh_scene(s, "cube.obj");
    const std::string cube = slurp(s.dir / "cube.obj");
    for (const std::string option : {"--checkpoint", "--trace", "--profile-json"}) {
        INFO(option);
        Run run = wavepath("render " + quoted(scene) + " --spp 1 " + option + " " +
                               quoted(s.dir / "cube.obj") + " --out " + quoted(s.dir / "x.exr"),
                           s);
        check_one_line_error(run, "cannot write " + option);
        CHECK(run.err.find("it is the same file as input file") != std::string::npos);
        CHECK(slurp(s.dir / "cube.obj") == cube);
    }
}

TEST_CASE("cli: export-mitsuba refuses to write a mesh over one the scene reads") {
    Scratch s;
    // The export names its meshes <stem>-<n>-<material>.ply: find the red
    // one's name with a first export, then give the input mesh that name.
    const fs::path scene = write_mesh_scene(s, "cube.ply", "cube_ascii.ply");
    Run probe = wavepath("export-mitsuba " + quoted(scene) + " " + quoted(s.dir / "probe.xml"), s);
    REQUIRE(probe.exit_code == 0);
    std::string generated;
    for (const auto& entry : fs::directory_iterator(s.dir)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("probe-", 0) == 0 && name.find("-red.ply") != std::string::npos)
            generated = "export" + name.substr(5);
    }
    REQUIRE(!generated.empty());
    fs::rename(s.dir / "cube.ply", s.dir / generated);
    std::string text = slurp(scene);
    text.replace(text.find("cube.ply"), 8, generated);
    s.write("mesh.json", text);
    const std::string mesh = slurp(s.dir / generated);
    Run run = wavepath("export-mitsuba " + quoted(scene) + " " + quoted(s.dir / "export.xml"), s);
    check_one_line_error(run, "it is the same file as input file");
    CHECK(slurp(s.dir / generated) == mesh);
    CHECK_FALSE(fs::exists(s.dir / "export.xml"));
}

TEST_CASE("cli: an output that is a device node is written through; a read-only one refused") {
    Scratch s;
    SECTION("a read-only file") {
        const fs::path out = s.write("theirs.exr", "someone else's");
        fs::permissions(out,
                        fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
        Run run = render("--out " + quoted(out), s);
        check_one_line_error(run, "the file is read-only");
        CHECK(run.err.find(" at 1 spp on ") == std::string::npos); // refused before the render
        CHECK(slurp(out) == "someone else's");
    }
    SECTION("a character device") {
        const fs::path null = s.dir / "null";
        if (!make_char_device(null, 3)) {
            WARN("mknod is not allowed here");
            return;
        }
        Run run = render("--out " + quoted(s.dir / "x.exr") + " --trace " + quoted(null) +
                             " --checkpoint " + quoted(null) + " --profile-json " + quoted(null),
                         s);
        INFO("stderr: " << run.err);
        CHECK(run.exit_code == 0);
        CHECK(is_char_device(null)); // not replaced by a regular file
    }
    SECTION("a FIFO nobody reads") {
        const fs::path fifo = s.dir / "fifo.json";
        REQUIRE(::mkfifo(fifo.c_str(), 0666) == 0);
        Run run = render(
            "--quiet --out " + quoted(s.dir / "x.exr") + " --profile-json " + quoted(fifo), s);
        // The render runs (someone may read by then); the write then fails.
        INFO("stderr: " << run.err);
        CHECK(run.exit_code == 1);
        CHECK(run.err.find("wavepath: error: cannot write '" + fifo.string() +
                           "': no process is reading the FIFO\n") != std::string::npos);
        struct stat st {};
        REQUIRE(::stat(fifo.c_str(), &st) == 0);
        CHECK(S_ISFIFO(st.st_mode));
    }
}

TEST_CASE("cli: a FIFO or device as an input is refused at once, naming the file") {
    Scratch s;
    const fs::path fifo = s.dir / "pipe.json";
    REQUIRE(::mkfifo(fifo.c_str(), 0666) == 0); // no writer: opening it would block for ever
    // timeout: a hang fails the test instead of stalling the suite.
    Run run = wavepath("render " + quoted(fifo) + " --spp 1", s, "timeout 30");
    check_one_line_error(run, "cannot open scene '" + fifo.string() + "': it is a FIFO");

    const fs::path scene = write_mesh_scene(s, "cube.obj");
    fs::remove(s.dir / "cube.obj");
    REQUIRE(::mkfifo((s.dir / "cube.obj").c_str(), 0666) == 0);
    run = wavepath("render " + quoted(scene) + " --spp 1", s, "timeout 30");
    check_one_line_error(run, "cube.obj");
    CHECK(run.err.find("it is a FIFO, not a regular file") != std::string::npos);
    fs::remove(s.dir / "cube.obj");
    if (make_char_device(s.dir / "cube.obj", 5)) { // endless, as /dev/zero
        run = wavepath("render " + quoted(scene) + " --spp 1", s, "timeout 30");
        check_one_line_error(run, "it is a character device, not a regular file");
    }

    run = render("--resume " + quoted(fifo) + " --out " + quoted(s.dir / "x.exr"), s);
    check_one_line_error(run, fifo.string());
    CHECK(run.err.find("it is a FIFO") != std::string::npos);
}

TEST_CASE("cli: an output that is an input or another output is refused before any work") {
    Scratch s;
    const std::string hexroom = slurp(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
    const fs::path scene = s.write("scene.json", hexroom);

    SECTION("the scene file, through '..'") {
        fs::create_directories(s.dir / "sub");
        const fs::path out = s.dir / "sub" / ".." / "scene.json";
        Run run = wavepath("render " + quoted(scene) + " --spp 1 --profile-json " + quoted(out), s);
        check_one_line_error(run, "it is the same file as the scene");
        CHECK(slurp(scene) == hexroom);
    }
    SECTION("the scene file, through a symbolic link") {
        fs::create_symlink(scene, s.dir / "link.json");
        Run run = wavepath("render " + quoted(scene) + " --spp 1 --trace " +
                               quoted(s.dir / "link.json") + " --out " + quoted(s.dir / "x.exr"),
                           s);
        check_one_line_error(run, "cannot write --trace");
        CHECK(slurp(scene) == hexroom);
        CHECK_FALSE(fs::exists(s.dir / "x.exr"));
    }
    SECTION("two outputs of one command") {
        const fs::path out = s.dir / "x.png";
        Run run = wavepath("render " + quoted(scene) + " --spp 1 --out " + quoted(out) + " --png " +
                               quoted(s.dir / "." / "x.png"),
                           s);
        check_one_line_error(run, "cannot write --png");
        CHECK(run.err.find("same file as --out") != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    }
    SECTION("converge: the reference and the CSV") {
        const fs::path reference = s.write("ref.exr", "not read before the check");
        Run run = wavepath("converge " + quoted(scene) + " --max-spp 1 --reference " +
                               quoted(reference) + " --out " + quoted(reference),
                           s);
        check_one_line_error(run, "same file as the reference");
        CHECK(slurp(reference) == "not read before the check");
        fs::path csv = s.dir / "a.csv";
        check_one_line_error(wavepath("converge " + quoted(scene) + " --max-spp 1 --csv " +
                                          quoted(csv) + " --overlay " + quoted(csv),
                                      s),
                             "same file as --overlay");
    }
    SECTION("compare: the diff over the image") {
        const fs::path image = s.write("image.pfm", "kept");
        check_one_line_error(
            wavepath("compare " + quoted(image) + " " + quoted(image) + " --diff " + quoted(image),
                     s),
            "cannot write --diff");
        CHECK(slurp(image) == "kept");
    }
    // Nothing was written beside the inputs (no temporary files either).
    for (const auto& entry : fs::directory_iterator(s.dir)) {
        const std::string name = entry.path().filename().string();
        CHECK(name.find(".tmp") == std::string::npos);
    }
}

TEST_CASE("cli: an output that cannot be written fails before the render") {
    Scratch s;
    SECTION("a read-only directory") {
        // Root writes through permission bits, so as root take a directory
        // of a read-only filesystem that refuses even root's new files.
        fs::path dir = "/sys";
        if (::geteuid() != 0) {
            dir = s.dir / "read-only";
            fs::create_directories(dir);
            fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
        }
        Run run = render("--out " + quoted(dir / "x.exr"), s);
        check_one_line_error(run, "cannot create files in directory");
        CHECK(run.err.find(" at 1 spp on ") == std::string::npos); // no render started
        if (dir != "/sys")                                         // so that Scratch can remove it
            fs::permissions(dir, fs::perms::owner_all, fs::perm_options::replace);
    }
    SECTION("a directory at the output path") {
        fs::create_directories(s.dir / "image.exr");
        check_one_line_error(render("--out " + quoted(s.dir / "image.exr"), s),
                             "it is a directory");
        check_one_line_error(
            render("--out " + quoted(s.dir / "x.exr") + " --png " + quoted(s.dir / "image.exr"), s),
            "it is a directory");
    }
    SECTION("a name too long once the temporary suffix is added") {
        // 240 bytes fit the usual 255-byte limit, but not with ".tmp-<pid>-<n>".
        const std::string name = std::string(236, 'n') + ".exr";
        Run run = render("--out " + quoted(s.dir / name), s);
        check_one_line_error(run, "file name too long (240 bytes");
    }
    SECTION("--png naming another format") {
        // The view is a PNG; an .exr named --png would hold the linear image.
        Run run =
            render("--out " + quoted(s.dir / "x.exr") + " --png " + quoted(s.dir / "view.exr"), s);
        check_one_line_error(run, "unsupported extension '.exr' (use .png)");
        CHECK_FALSE(fs::exists(s.dir / "view.exr"));
    }
    SECTION("--exposure nan") {
        for (const std::string value : {"nan", "inf", "-inf", "x"}) {
            INFO(value);
            Run run = render("--exposure " + value + " --out " + quoted(s.dir / "x.png"), s);
            check_one_line_error(run, "--exposure");
            CHECK(run.err.find("finite") != std::string::npos);
        }
    }
    CHECK_FALSE(fs::exists(s.dir / "x.exr"));
    CHECK_FALSE(fs::exists(s.dir / "x.png"));
}

TEST_CASE("cli: converge checks its reference before rendering") {
    Scratch s;
    wp::Image reference(4, 4);
    const fs::path small = s.dir / "small.pfm";
    wp::write_image(small, reference);
    check_one_line_error(wavepath("converge " + kHexroom + " --max-spp 1 --width 8 --height 8 " +
                                      "--reference " + quoted(small),
                                  s),
                         "is 4x4 but the render is 8x8");
    reference.rgb[5] = std::numeric_limits<float>::quiet_NaN();
    reference.rgb[9] = std::numeric_limits<float>::infinity();
    const fs::path bad = s.dir / "bad.pfm";
    wp::write_image(bad, reference);
    Run run = wavepath(
        "converge " + kHexroom + " --max-spp 1 --width 4 --height 4 --reference " + quoted(bad), s);
    check_one_line_error(run, "has 2 NaN or infinite values");
    CHECK(run.out.find("spp") == std::string::npos); // the table never started
}

TEST_CASE("cli: NaN durations and options that would be ignored are refused before any work") {
    Scratch s;
    const std::string out = " --out " + quoted(s.dir / "x.exr");
    const std::string scene = " " + kHexroom;
    struct Case {
        std::string arguments;
        std::string what;
    };
    for (const Case& c : {
             Case{"render" + scene + " --checkpoint " + quoted(s.dir / "c.ckpt") +
                      " --checkpoint-every nan" + out,
                  "expected a positive finite number, got 'nan'"},
             Case{"converge" + scene + " --max-time nan" + out,
                  "expected a positive finite number, got 'nan'"},
             Case{"breakdown" + scene + " --spp 2,4 --light-threshold nan",
                  "expected a positive finite number, got 'nan'"},
             Case{"render" + scene + " --checkpoint-every 5" + out, "--checkpoint"},
             Case{"render" + scene + " --preview-bind 127.0.0.1" + out, "--preview"},
         }) {
        INFO(c.arguments);
        Run run = wavepath(c.arguments, s);
        check_one_line_error(run, c.what);
        CHECK(run.exit_code == 2); // refused by the option parser: nothing was built
    }
    CHECK_FALSE(fs::exists(s.dir / "x.exr"));
}

TEST_CASE("cli: a range error states its bounds in a few digits") {
    // CLI::PositiveNumber, the validator these options had, reports
    // "not in range 0.000000 to 1797...", the largest double in 309 digits.
    Scratch s;
    const std::string out = " --out " + quoted(s.dir / "x.exr");
    const std::string scene = " " + kHexroom;
    for (const std::string& arguments : {
             "render" + scene + " --checkpoint " + quoted(s.dir / "c.ckpt") +
                 " --checkpoint-every 0" + out,
             "render" + scene + " --time -1" + out,
             "render" + scene + " --target-error 0" + out,
             "converge" + scene + " --max-time 0" + out,
             "breakdown" + scene + " --spp 2,4 --light-threshold -1",
             "render" + scene + " --spp 0" + out,
             "render" + scene + " --width 99999" + out,
         }) {
        INFO(arguments);
        Run run = wavepath(arguments, s);
        check_one_line_error(run, "--");
        CHECK(run.exit_code == 2);
        std::size_t digits = 0, longest = 0;
        for (const char c : run.err) {
            digits = c >= '0' && c <= '9' ? digits + 1 : 0;
            longest = std::max(longest, digits);
        }
        CHECK(longest <= 12);
        CHECK(run.err.size() < 200 + s.dir.string().size());
    }
}
