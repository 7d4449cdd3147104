// The commands on a scene with instances: `info` prints the instances and
// their device bytes, `render --traversal loop` is refused in one line, and
// `export-mitsuba` says what it wrote.
#include "cli_run.hpp"

#include <string>

using namespace wp::test::cli;

namespace {

const std::string kScene = WAVEPATH_SOURCE_DIR "/tests/data/mitsuba/instances.xml";

} // namespace

TEST_CASE("cli: info prints a scene's instances and their device bytes", "[cli][instances]") {
    Scratch scratch;
    const Run run = wavepath("info '" + kScene + "'", scratch);
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.out.find("  instances: 5 of 2 shape groups (") != std::string::npos);
    CHECK(run.out.find("instances on the device: ") != std::string::npos);
    CHECK(run.out.find(" for 5 instances, placing ") != std::string::npos);
    CHECK(run.out.find("features: ") != std::string::npos);
    CHECK(run.out.find(" instances; bvh") != std::string::npos);
}

TEST_CASE("cli: --traversal loop on a scene with instances is one line", "[cli][instances]") {
    Scratch scratch;
    const Run run = wavepath("render '" + kScene + "' --spp 1 --traversal loop --out '" +
                                 (scratch.dir / "x.exr").string() + "'",
                             scratch);
    check_one_line_error(run, "a scene with instances is traced through its hierarchy only");
    CHECK_FALSE(std::filesystem::exists(scratch.dir / "x.exr"));
}

TEST_CASE("cli: export-mitsuba counts the shapegroups and instances it wrote", "[cli][instances]") {
    Scratch scratch;
    const Run run = wavepath(
        "export-mitsuba '" + kScene + "' '" + (scratch.dir / "e.xml").string() + "'", scratch);
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.out.find(", 2 shapegroups and 5 instances") != std::string::npos);
}
