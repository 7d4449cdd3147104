// `render --device LIST`: several devices in one process (PoCL shows the CPU
// as two devices with POCL_DEVICES="pthread pthread"), and the errors of a
// bad list.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/cli_run.hpp"
#include "app/same_samples.hpp"
#include "image/exr.hpp"
#include "image/image_io.hpp"

using namespace wp::test::cli;

namespace {

const std::string kTwoCpuDevices = "POCL_DEVICES='pthread pthread'";

bool on_pocl() {
    return wp::test::device_info().platform_name.find("Portable Computing Language") !=
           std::string::npos;
}

} // namespace

TEST_CASE("cli multi-device: a bad entry in the device list is one line naming it") {
    Scratch s;
    const std::string to =
        " --spp 1 --width 4 --height 4 --out '" + (s.dir / "x.exr").string() + "'";
    check_one_line_error(
        wavepath("render " + kHexroom + to + " --device " + test_device_index() + ",9:9", s),
        "no OpenCL device has index '9:9'");
    check_one_line_error(
        wavepath("render " + kHexroom + to + " --device " + test_device_index() + ",no-such-gpu",
                 s),
        "no OpenCL device name contains 'no-such-gpu'");
    check_one_line_error(
        wavepath("render " + kHexroom + to + " --device " + test_device_index() + ",", s),
        "has an empty entry");
    check_one_line_error(wavepath("render " + kHexroom + to + " --device " + test_device_index() +
                                      "," + test_device_index(),
                                  s),
                         "appears twice in the device list");
    // Commands that run on one device say so of a list. ("all" is that
    // device on a one-device machine: tests/cl/test_device_select.cpp.)
    check_one_line_error(wavepath("info " + kHexroom + " --device " + test_device_index() + "," +
                                      test_device_index(),
                                  s),
                         "runs on one device");
    CHECK_FALSE(std::filesystem::exists(s.dir / "x.exr"));
}

TEST_CASE("cli multi-device: two devices render the image one device renders") {
    if (!on_pocl()) {
        WARN("skipped: the test device is not PoCL's, which can show the CPU as two devices");
        return;
    }
    Scratch s;
    const std::uint32_t spp = 12;
    const std::string common = "render " + kHexroom + " --spp " + std::to_string(spp) +
                               " --width 40 --height 30 --seed 9 --out ";
    const auto one = s.dir / "one.exr", two = s.dir / "two.exr";
    Run single = wavepath(common + "'" + one.string() + "' --device 0:0", s, kTwoCpuDevices);
    INFO(single.err);
    REQUIRE(single.exit_code == 0);
    Run multi = wavepath(common + "'" + two.string() + "' --device all --profile-json '" +
                             (s.dir / "p.json").string() + "'",
                         s, kTwoCpuDevices);
    INFO(multi.err);
    REQUIRE(multi.exit_code == 0);
    CHECK(multi.err.find("(0:0) + ") != std::string::npos);
    check_same_samples(wp::read_image(two), wp::read_image(one), spp);

    // The profile splits the samples between the two, and they add up.
    const std::string json = slurp(s.dir / "p.json");
    CHECK(json.find("\"devices\"") != std::string::npos);
    CHECK(json.find("\"index\": \"0:1\"") != std::string::npos);
    CHECK(json.find("\"idle_seconds\"") != std::string::npos);
    // The same devices named twice by name: each name takes the next match.
    Run by_name = wavepath(common + "'" + two.string() + "' --device pthread,pthread --profile", s,
                           kTwoCpuDevices);
    INFO(by_name.err);
    REQUIRE(by_name.exit_code == 0);
    CHECK(by_name.out.find("0:0   pthread") != std::string::npos);
    CHECK(by_name.out.find("0:1   pthread") != std::string::npos);
    CHECK(by_name.out.find("split of 40x30 at 12 spp over 2 devices") != std::string::npos);
    check_same_samples(wp::read_image(two), wp::read_image(one), spp);
}

TEST_CASE("cli multi-device: two devices give the AOVs one device gives", "[aov]") {
    if (!on_pocl()) {
        WARN("skipped: the test device is not PoCL's, which can show the CPU as two devices");
        return;
    }
    Scratch s;
    const std::string common = "render " + kHexroom +
                               " --spp 6 --width 24 --height 16 --seed 9 --aov "
                               "albedo,normal,depth --out ";
    const auto one = s.dir / "one.exr", two = s.dir / "two.exr";
    Run single = wavepath(common + "'" + one.string() + "' --device 0:0", s, kTwoCpuDevices);
    INFO(single.err);
    REQUIRE(single.exit_code == 0);
    Run multi = wavepath(common + "'" + two.string() + "' --device all", s, kTwoCpuDevices);
    INFO(multi.err);
    REQUIRE(multi.exit_code == 0);
    CHECK(multi.err.find("(0:0) + ") != std::string::npos);
    const auto a = wp::read_exr_channels(one), b = wp::read_exr_channels(two);
    REQUIRE(a.size() == 10);
    REQUIRE(b.size() == 10);
    for (const auto& [name, values] : a) {
        if (name.find('.') == std::string::npos)
            continue; // R, G, B: the test above
        INFO(name);
        const std::vector<float>& other = b.at(name);
        REQUIRE(other.size() == values.size());
        // Each device's share of a pixel's samples is in its AOVs: a lost
        // share would halve the mean, not move it by rounding.
        double worst = 0.0;
        for (std::size_t i = 0; i < values.size(); ++i)
            worst = std::max(worst, static_cast<double>(std::abs(values[i] - other[i])) /
                                        std::max(1.0, static_cast<double>(std::abs(values[i]))));
        CHECK(worst < 1e-5);
    }
}
