// Outputs are checked before any work: one that would overwrite an input or
// another output, and one that could not be written, are refused at once,
// and a value that would make the result meaningless is refused with them.
#include <catch2/catch.hpp>

#include <filesystem>
#include <limits>
#include <string>

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

} // namespace

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
