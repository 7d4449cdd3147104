// --aov on the command line: the EXR gains the layers asked for beside an
// unchanged beauty image; a bad list and an output that is not an EXR are
// refused in one line before any work; checkpoints carry the AOVs.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "app/cli_run.hpp"
#include "image/exr.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

Run render(const std::string& flags, const Scratch& s) {
    return wavepath("render " + kHexroom + " --spp 2 --width 8 --height 6 " + flags, s);
}

std::string out_flag(const Scratch& s, const std::string& name) {
    return " --out '" + (s.dir / name).string() + "'";
}

} // namespace

TEST_CASE("cli: --aov writes the layers asked for beside a beauty image that is unchanged bit "
          "for bit",
          "[cli][aov]") {
    Scratch s;
    REQUIRE(render(out_flag(s, "plain.exr"), s).exit_code == 0);
    Run run = render(out_flag(s, "aov.exr") + " --aov depth,albedo,normal", s);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    const auto plain = wp::read_exr_channels(s.dir / "plain.exr");
    const auto aov = wp::read_exr_channels(s.dir / "aov.exr");
    CHECK(plain.size() == 3);
    CHECK(aov.size() == 10);
    for (const char* name : {"R", "G", "B"}) {
        INFO(name);
        REQUIRE(aov.count(name) == 1);
        CHECK(aov.at(name) == plain.at(name)); // float for float
    }
    for (const char* name :
         {"albedo.R", "albedo.G", "albedo.B", "normal.X", "normal.Y", "normal.Z", "depth.Z"}) {
        INFO(name);
        REQUIRE(aov.count(name) == 1);
        CHECK(aov.at(name).size() == 8 * 6);
    }
    // The hexroom's camera sees a wall in every pixel: a positive depth, a
    // unit normal (a mean of unit normals of one wall), a non-black albedo.
    for (std::size_t p = 0; p < 8 * 6; ++p) {
        CHECK(aov.at("depth.Z")[p] > 0.0f);
        const float x = aov.at("normal.X")[p], y = aov.at("normal.Y")[p], z = aov.at("normal.Z")[p];
        CHECK(x * x + y * y + z * z <= 1.0f + 1e-5f);
        CHECK(aov.at("albedo.R")[p] + aov.at("albedo.G")[p] + aov.at("albedo.B")[p] > 0.0f);
    }

    // The metadata names them, in AOV order; a render without them does not.
    const auto has_aovs_entry = [](const fs::path& path, const std::string& value) {
        for (const auto& [key, text] : wp::read_exr_summary(path).metadata)
            if (key == "wavepath.aovs")
                return text == value;
        return value.empty();
    };
    CHECK(has_aovs_entry(s.dir / "aov.exr", "albedo,normal,depth"));
    CHECK(has_aovs_entry(s.dir / "plain.exr", ""));

    Run some = render(out_flag(s, "depth.exr") + " --aov depth", s);
    REQUIRE(some.exit_code == 0);
    const auto depth = wp::read_exr_channels(s.dir / "depth.exr");
    CHECK(depth.size() == 4);
    CHECK(depth.count("depth.Z") == 1);
    CHECK(depth.at("depth.Z") == aov.at("depth.Z"));
}

TEST_CASE("cli: a bad --aov is refused in one line naming the option, nothing written",
          "[cli][aov]") {
    Scratch s;
    const fs::path out = s.dir / "x.exr";
    for (const char* list : {"albedo,colour", "depth,depth", "", "albedo,", ",normal"}) {
        INFO("--aov '" << list << "'");
        Run run = render(out_flag(s, "x.exr") + " --aov '" + std::string(list) + "'", s);
        check_one_line_error(run, "--aov");
        CHECK_FALSE(fs::exists(out));
    }
    Run png = render(out_flag(s, "x.png") + " --aov depth", s);
    check_one_line_error(png, "--aov: the AOVs are layers of an EXR");
    CHECK_FALSE(fs::exists(s.dir / "x.png"));
}

TEST_CASE("cli: a render with --aov resumed from its checkpoint has the AOVs and image of one "
          "that was never stopped, bit for bit",
          "[cli][aov]") {
    Scratch s;
    const std::string checkpoint = " --checkpoint '" + (s.dir / "c.wpck").string() + "'";
    const std::string resume = " --resume '" + (s.dir / "c.wpck").string() + "'";
    auto run = [&](const std::string& flags) {
        return wavepath(
            "render " + kHexroom + " --width 8 --height 6 --aov albedo,normal,depth " + flags, s);
    };
    REQUIRE(run("--spp 5" + out_flag(s, "whole.exr")).exit_code == 0);
    REQUIRE(run("--spp 2" + out_flag(s, "part.exr") + checkpoint).exit_code == 0);
    Run resumed = run("--spp 5" + out_flag(s, "resumed.exr") + resume);
    INFO(resumed.err);
    REQUIRE(resumed.exit_code == 0);
    const auto whole = wp::read_exr_channels(s.dir / "whole.exr");
    const auto again = wp::read_exr_channels(s.dir / "resumed.exr");
    REQUIRE(whole.size() == 10);
    for (const auto& [name, values] : whole) {
        INFO(name);
        REQUIRE(again.count(name) == 1);
        CHECK(again.at(name) == values);
    }
    // Its options name the AOV kernels: a render without --aov does not resume it.
    Run plain = wavepath("render " + kHexroom + " --width 8 --height 6 --spp 5" +
                             out_flag(s, "plain.exr") + resume,
                         s);
    check_one_line_error(plain, "other options");
    CHECK_FALSE(fs::exists(s.dir / "plain.exr"));
}
