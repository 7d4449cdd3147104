// The progress report of `wavepath render` on stderr (app/progress.hpp):
// plain lines in a log, a line redrawn in place on a terminal, nothing with
// --quiet.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

#include "app/cli_run.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

struct ProgressLine {
    double spp = 0.0;
    int percent = 0;
    double elapsed = 0.0;
    double samples_per_second = 0.0;
    double left = 0.0;
    bool has_error = false;
};

std::vector<ProgressLine> progress_lines(const std::string& err, std::uint32_t spp_goal) {
    const std::regex line("wavepath: progress: ([0-9.]+)/" + std::to_string(spp_goal) +
                          " spp \\(([0-9]+)%\\), ([0-9.]+)s, ([0-9.e+]+) samples/s, ([0-9.]+)s "
                          "left(, relMSE [0-9.e+-]+)?\n");
    std::vector<ProgressLine> lines;
    for (auto it = std::sregex_iterator(err.begin(), err.end(), line); it != std::sregex_iterator();
         ++it) {
        const std::smatch& m = *it;
        lines.push_back({std::stod(m[1]), std::stoi(m[2]), std::stod(m[3]), std::stod(m[4]),
                         std::stod(m[5]), m[6].matched});
    }
    return lines;
}

} // namespace

TEST_CASE("cli: without a terminal, progress is a plain line every tenth of the way") {
    Scratch s;
    const int width = 160, height = 120;
    const auto start = std::chrono::steady_clock::now();
    const Run run = wavepath("render " + kHexroom + " --width 160 --height 120 --spp 20 --out '" +
                                 (s.dir / "out.exr").string() + "'",
                             s);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.find('\r') == std::string::npos); // no control characters in a log
    CHECK(run.err.find('\033') == std::string::npos);
    const std::vector<ProgressLine> lines = progress_lines(run.err, 20);
    // Every line is one of them: the start line and the progress lines.
    CHECK(static_cast<std::size_t>(std::count(run.err.begin(), run.err.end(), '\n')) ==
          lines.size() + 1);
    // One per tenth, and one more every five seconds.
    CHECK(lines.size() >= 10);
    CHECK(lines.size() <= 10 + static_cast<std::size_t>(wall / 5.0) + 1);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const ProgressLine& l = lines[i];
        INFO("line " << i << ": " << l.spp << " spp, " << l.percent << "%, " << l.elapsed << " s, "
                     << l.samples_per_second << " samples/s");
        // The part of the way done is the spp's, rounded down.
        CHECK(std::abs(l.percent - std::floor(l.spp / 20.0 * 100.0)) <= 1.0);
        if (i > 0) {
            CHECK(l.percent > lines[i - 1].percent);
            CHECK(l.spp >= lines[i - 1].spp);
        }
        // Samples per second are samples over the elapsed time, which is
        // printed to a tenth of a second (and the rate to three digits).
        const double samples = l.spp * width * height;
        if (l.elapsed >= 0.2) {
            CHECK(l.samples_per_second >= 0.995 * samples / (l.elapsed + 0.05));
            CHECK(l.samples_per_second <= 1.005 * samples / (l.elapsed - 0.05));
            // The time left at this rate, to the roundings of both times.
            const double rounding = 0.05 * (20.0 - l.spp) / l.spp + 0.05;
            CHECK(std::abs(l.left - l.elapsed * (20.0 - l.spp) / l.spp) <=
                  rounding + 0.01 * l.left);
        }
    }
    REQUIRE(!lines.empty());
    CHECK(lines.back().percent == 100);
    CHECK(lines.back().spp == 20.0);
    CHECK(lines.back().left == 0.0);
    CHECK(lines.back().has_error); // from 2 spp on
}

TEST_CASE("cli: --quiet reports no progress") {
    Scratch s;
    const Run run = wavepath("render " + kHexroom + " --width 32 --height 24 --spp 20 --quiet " +
                                 "--out '" + (s.dir / "out.exr").string() + "'",
                             s);
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.find("progress") == std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1); // the start line alone
    CHECK(run.err.find(" at 20 spp on ") != std::string::npos);
    CHECK(run.out.find("32x24, 20 spp") != std::string::npos);
}

TEST_CASE("cli: on a terminal, progress is one line redrawn in place") {
    if (std::system("command -v script >/dev/null 2>&1") != 0) {
        WARN("skipped: script (util-linux) is not installed, so there is no pseudo-terminal");
        return;
    }
    Scratch s;
    const fs::path log = s.dir / "terminal.txt";
    // script runs the command on a pseudo-terminal and copies what it shows.
    const std::string command = "script -qec \"'" + std::string(WAVEPATH_EXE) + "' render " +
                                kHexroom + " --width 160 --height 120 --spp 20 --device " +
                                test_device_index() + " --out '" + (s.dir / "out.exr").string() +
                                "'\" /dev/null > '" + log.string() + "' 2>&1 < /dev/null";
    REQUIRE(std::system(command.c_str()) == 0);
    const std::string shown = slurp(log);
    INFO("terminal: " << shown);
    CHECK(shown.find("wavepath: progress:") == std::string::npos); // not the plain lines
    // Redrawn: carriage returns, each drawing of the bar ending in "erase to
    // the end of the line", the last at 20/20 spp with the bar full and an
    // error estimate.
    const std::regex drawing("\r\\[([#.]{30})\\] ([0-9.]+)/20 spp  [0-9.]+s  [0-9.e+]+ samples/s"
                             "  ETA [0-9.]+s(, relMSE [0-9.e+-]+)?\033\\[K");
    std::vector<std::smatch> drawings;
    for (auto it = std::sregex_iterator(shown.begin(), shown.end(), drawing);
         it != std::sregex_iterator(); ++it)
        drawings.push_back(*it);
    REQUIRE(drawings.size() >= 2);
    const std::smatch& last = drawings.back();
    CHECK(last[1].str() == std::string(30, '#'));
    CHECK(last[2].str() == "20.0");
    CHECK(last[3].matched);
    // The bar ends its line before the summary.
    CHECK(shown.find("\033[K\r\n") != std::string::npos); // the terminal turns \n into \r\n
}
