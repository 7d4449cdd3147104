// The vectoriser-remark capture (tests/support/vectorizer_remarks.hpp) that
// the vectorisation guards rely on: on PoCL, every stage kernel's work-group
// loop gets a verdict of the loop vectoriser, attributed to that kernel.
#include <catch2/catch.hpp>

#include "support/vectorizer_remarks.hpp"

using namespace wp;

TEST_CASE("vectorizer remarks: each stage kernel's work-group loop has a verdict") {
    if (!test::test_device_is_pocl()) {
        WARN("skipped: the vectoriser remarks are PoCL's, and the test device is not PoCL");
        return;
    }
    const test::VectorizerRemarks remarks =
        test::capture_vectorizer_remarks(WAVEPATH_SOURCE_DIR "/scenes/hexroom.json");
    REQUIRE(remarks.captured);
    for (const char* kernel : {"generate", "intersect", "shade", "shadow", "accumulate"}) {
        INFO(kernel);
        CHECK_FALSE(remarks.of_kernel(kernel).empty());
        // Vectorised, or a stated reason why not: the verdict a guard tests.
        CHECK((remarks.vectorized(kernel) ||
               !remarks.matching(kernel, "loop not vectorized").empty()));
    }
    CHECK(remarks.of_kernel("no_such_kernel").empty());
}
