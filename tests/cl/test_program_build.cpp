// Building kernels: embedded includes, and a failed build's diagnostics.
#include <algorithm>

#include <catch2/catch.hpp>

#include "cl/program.hpp"
#include "support/test_device.hpp"

using namespace wp;

TEST_CASE("program: includes resolve to embedded files, each once, with #line markers") {
    std::string text =
        expand_includes("#include \"rng.h\"\n#include \"wp_shared.h\"\nint x;\n", "t.cl");
    CHECK(text.find("wp_mix32") != std::string::npos);
    // wp_shared.h is included by rng.h and again by t.cl: its text appears once.
    std::size_t first = text.find("WP_SHARED_H");
    REQUIRE(first != std::string::npos);
    CHECK(text.find("#define WP_SHARED_H") == text.rfind("#define WP_SHARED_H"));
    // After the includes, line numbers resume in t.cl at its line 3.
    CHECK(text.find("#line 3 \"t.cl\"\nint x;") != std::string::npos);
    CHECK_THROWS_AS(expand_includes("#include \"missing.h\"\n", "t.cl"), std::out_of_range);
}

TEST_CASE("program: a failed build reports the compiler log with file and line") {
    DeviceContext& device = test::device();
    const char* source = "#include \"wp_shared.h\"\n"
                         "__kernel void broken(__global float* out) {\n"
                         "    out[0] = no_such_variable;\n"
                         "}\n";
    try {
        build_program(device.context, device.info.device, source, "broken.cl", "");
        FAIL("the build should have failed");
    } catch (const BuildError& e) {
        INFO(e.log());
        CHECK(std::string(e.what()).find("broken.cl") != std::string::npos);
        CHECK(e.log().find("broken.cl:3") != std::string::npos);
        CHECK(e.log().find("no_such_variable") != std::string::npos);
    }
}

TEST_CASE("program: a log that numbers the expanded text's lines is given the original ones") {
    // NVIDIA's compiler ignores #line and names lines of the text it was
    // given, as "<kernel>:LINE:COLUMN" (seen on the H200, docs/gpu.md).
    const std::string expanded =
        expand_includes("#include \"rng.h\"\nint x;\nint y = z;\n", "t.cl");
    std::size_t line_of_y = 1;
    for (std::size_t i = 0; i < expanded.find("int y"); ++i)
        line_of_y += expanded[i] == '\n';
    const std::string log = "<kernel>:" + std::to_string(line_of_y) +
                            ":9: error: use of undeclared identifier 'z'\n<built-in>:1: note";
    CHECK(log_with_source_lines(log, expanded) ==
          "t.cl:3:9: error: use of undeclared identifier 'z'\n<built-in>:1: note");
    // A line inside an included header names that header.
    const std::size_t header_line =
        1 + static_cast<std::size_t>(
                std::count(expanded.begin(), expanded.begin() + expanded.find("wp_mix32"), '\n'));
    CHECK(log_with_source_lines("<source>:" + std::to_string(header_line) + ": x", expanded)
              .rfind("rng.h:", 0) == 0);
    // Lines past the text, and logs without such locations, are left alone.
    CHECK(log_with_source_lines("<kernel>:99999:1: e", expanded) == "<kernel>:99999:1: e");
    CHECK(log_with_source_lines("t.cl:3:9: error <", expanded) == "t.cl:3:9: error <");
    CHECK(log_with_source_lines("see <kernel>:" + std::to_string(line_of_y), expanded) ==
          "see t.cl:3");
}

TEST_CASE("program: every stage of the wavefront program builds") {
    DeviceContext& device = test::device();
    BuiltProgram built = build_wavefront_program(device.context, device.info.device, "");
    for (const char* name : {"generate", "intersect", "shade", "shadow", "accumulate"})
        CHECK_NOTHROW(cl::Kernel(built.program, name));
}
