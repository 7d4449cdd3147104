// Messages for mistakes that are not about a scene's values: a mistyped
// subcommand, invalid UTF-8, a scene without light, output that cannot go to
// standard output.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/cli_run.hpp"
#include "support/sanitizer.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

TEST_CASE("cli: a mistyped subcommand suggests the nearest") {
    Scratch s;
    Run run = wavepath("rendr " + kHexroom, s);
    check_one_line_error(run, "unknown subcommand 'rendr'; did you mean 'render'?");
    CHECK(run.exit_code == 2);
    check_one_line_error(wavepath("converg " + kHexroom, s), "did you mean 'converge'?");
    Run far = wavepath("xyzzy", s);
    check_one_line_error(far, "unknown subcommand 'xyzzy'; expected one of devices, render,");
    // An option where the subcommand should be keeps CLI11's own message.
    Run option = wavepath("--bogus", s);
    check_one_line_error(option, "wavepath: error: ");
    CHECK(option.err.find("unknown subcommand") == std::string::npos);
}

TEST_CASE("cli: invalid UTF-8 is reported at the key it is in") {
    Scratch s;
    std::string scene = slurp(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json");
    const fs::path out = s.dir / "x.pfm";
    SECTION("in a key") {
        // The second material's key gets an invalid byte.
        scene.replace(scene.find("\"left_wall\":"), 12, "\"le\xfft_wall\":");
        const fs::path bad = s.write("key.json", scene);
        Run run = wavepath("render '" + bad.string() + "' --out '" + out.string() + "'", s);
        check_one_line_error(run, "key.json:");
        CHECK(run.err.find(": /materials: invalid JSON: ") != std::string::npos);
        CHECK(run.err.find("(in the key after 'back_left_wall')") != std::string::npos);
        CHECK(run.err.find('\xff') == std::string::npos); // the message is valid UTF-8
    }
    SECTION("in a value") {
        scene.replace(scene.find("\"diffuse\""), 9, "\"diff\xc3use\"");
        const fs::path bad = s.write("value.json", scene);
        Run run = wavepath("render '" + bad.string() + "' --out '" + out.string() + "'", s);
        check_one_line_error(run, ": /materials/back_left_wall/type: invalid JSON: ");
        CHECK(run.err.find("in the key") == std::string::npos);
    }
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("cli: a scene with no emitter gets a warning") {
    Scratch s;
    const fs::path scene = s.write("dark.json", R"({
      "camera": {"eye": [-4, 0, 1], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 40, "resolution": [4, 4]},
      "materials": {"white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
                    "light": {"type": "emitter", "radiance": [1, 1, 1]}},
      "shapes": [{"type": "quad", "material": "white", "vertices": [[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]]}]})");
    const std::string to = " --spp 1 --out '" + (s.dir / "x.pfm").string() + "'";
    Run dark = wavepath("render '" + scene.string() + "'" + to, s);
    INFO(dark.err);
    REQUIRE(dark.exit_code == 0);
    CHECK(dark.err.find("wavepath: warning: " + scene.string() + ": no shape emits light") !=
          std::string::npos);
    Run lit = wavepath("render " + kHexroom + to, s);
    REQUIRE(lit.exit_code == 0);
    CHECK(lit.err.find("no shape emits light") == std::string::npos);
}

TEST_CASE("cli: a failed write to standard output is a failure") {
    REQUIRE(fs::exists("/dev/full"));
    for (const std::string command : {"devices", "--help", "render --help"}) {
        INFO(command);
        const std::string shell =
            "'" + std::string(WAVEPATH_EXE) + "' " + command + " >/dev/full 2>/dev/null";
        const int status = std::system(shell.c_str());
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) != 0);
        // And to a working stdout the same command succeeds.
        const std::string fine =
            "'" + std::string(WAVEPATH_EXE) + "' " + command + " >/dev/null 2>/dev/null";
        const int ok = std::system(fine.c_str());
        CHECK((WIFEXITED(ok) && WEXITSTATUS(ok) == 0));
    }
}

TEST_CASE("cli: the program cache and PoCL's kernel cache stay bounded") {
    Scratch s;
    const fs::path cache = s.dir / "cache";
    // Old entries bigger than the bounds (sparse files: no disk used).
    auto make = [](const fs::path& path, std::uintmax_t bytes) {
        fs::create_directories(path.parent_path());
        std::ofstream(path).put('x');
        fs::resize_file(path, bytes);
        fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::hours(24));
    };
    make(cache / "0000000000000000.clbin", 300ull << 20);
    make(cache / "pocl" / "ZZ" / "OLDPROGRAM" / "program.bc", 600ull << 20);
    // What PoCL leaves behind: an empty temporary file, a day old, and one a
    // compile might be writing now.
    make(cache / "pocl" / "tempfile_AbC123", 0);
    std::ofstream(cache / "pocl" / "tempfile_Now456").put('x');
    const std::string arguments = "render " + kHexroom + " --spp 1 --width 4 --height 4 --out '" +
                                  (s.dir / "x.pfm").string() + "'";
    Run run = wavepath(arguments, s, "WAVEPATH_CACHE_DIR='" + cache.string() + "' POCL_CACHE_DIR=");
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK_FALSE(fs::exists(cache / "0000000000000000.clbin"));
    CHECK_FALSE(fs::exists(cache / "pocl" / "ZZ" / "OLDPROGRAM"));
    CHECK_FALSE(fs::exists(cache / "pocl" / "tempfile_AbC123"));
    CHECK(fs::exists(cache / "pocl" / "tempfile_Now456"));
    // This run's kernels went to PoCL's cache, inside wavepath's; the
    // wavefront program itself is left to PoCL's cache (CacheOutcome::Driver).
    std::size_t programs = 0, pocl_files = 0;
    for (const auto& entry : fs::directory_iterator(cache))
        programs += entry.path().extension() == ".clbin";
    for (const auto& entry : fs::recursive_directory_iterator(cache / "pocl"))
        pocl_files += entry.is_regular_file();
    CHECK(programs == 0);
    CHECK(pocl_files >= 1);
}

TEST_CASE("cli: out of host memory names the allocation and its size") {
    if (wp::test::kAddressSanitizer) {
        WARN("skipped under AddressSanitizer: its shadow memory needs more address space "
             "than the ulimit -v this test sets");
        return;
    }
    Scratch s;
    const fs::path out = s.dir / "x.exr";
    // 3 GB of address space: enough to start and for the device's buffers of
    // 1024 path slots (PoCL's device memory is host memory), not for a
    // 6144x6144 film. (More pixels make PoCL itself abort on its failed
    // allocation before the film's turn.)
    const std::string command = "bash -c \"ulimit -v 3000000; WAVEPATH_DEVICE='" +
                                test_device_index() + "' '" + WAVEPATH_EXE + "' render " +
                                kHexroom +
                                " --width 6144 --height 6144 --pool 1024 --spp 1 --out '" +
                                out.string() + "'\" 2>'" + (s.dir / "err.txt").string() + "'";
    const int status = std::system(command.c_str());
    Run run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.err = slurp(s.dir / "err.txt");
    check_one_line_error(
        run, "out of host memory: the film of 6144x6144 pixels needs 3168 MiB (try a smaller");
    CHECK_FALSE(fs::exists(out));
}
