// `wavepath kernel-source` (hidden; .ci/gpu-targets-check): the build options
// a render passes, and the program text with its includes expanded.
#include <catch2/catch.hpp>

#include <string>

#include "app/cli_run.hpp"

using namespace wp::test::cli;

TEST_CASE("cli: kernel-source prints a render's build options and writes the source") {
    Scratch s;
    const fs::path source = s.dir / "wavefront.cl";
    std::string command = "kernel-source " + kHexroom + " --source ";
    Run specialised = wavepath(command.append(source.string()), s);
    REQUIRE(specialised.exit_code == 0);
    CHECK(specialised.out.find("-D WP_TRIANGLE_COUNT=26 -D WP_SPHERE_COUNT=2") !=
          std::string::npos);
    const std::string text = slurp(source);
    CHECK(text.find("__kernel void shade") != std::string::npos);
    CHECK(text.find("#include \"") == std::string::npos); // every kernel include expanded

    Run general = wavepath("kernel-source " + kHexroom + " --general", s);
    REQUIRE(general.exit_code == 0);
    CHECK(general.out.find("WP_TRIANGLE_COUNT") == std::string::npos);
    CHECK(general.out.find("-D WP_HAS_SHADING_NORMALS=1") != std::string::npos);
}
