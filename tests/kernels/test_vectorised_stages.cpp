// PoCL's work-group vectoriser must vectorise the tracing stages of a small
// scene's specialised program: that is most of their speed (3-4x,
// docs/specialization.md), and it holds only while no vector-typed
// instruction or unconvertible branch appears anywhere in the stage's body
// (kernels/traverse.h), which any later edit could break without changing a
// single result.
#include <catch2/catch.hpp>

#include <string>

#include "support/vectorizer_remarks.hpp"

namespace wp::test {
namespace {

const std::string kHexroomPath = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";

// The loop vectoriser's verdicts for a stage, for a failure message.
std::string verdicts(const VectorizerRemarks& remarks, const char* stage) {
    std::string out;
    for (const char* verdict : {"vectorized loop", "loop not vectorized"})
        for (const std::string& line : remarks.matching(stage, verdict))
            out += line + '\n';
    return out;
}

} // namespace

// One capture (a cold build of the hexroom's kernels) serves both checks.
TEST_CASE("The hexroom's specialised stages: each work-group loop has a verdict of its own, and "
          "intersect's and shadow's are vectorised",
          "[kernels][vectorise]") {
    if (!test_device_is_pocl()) {
        WARN("skipped: the tests do not run on PoCL, whose vectoriser this reads");
        return;
    }
    const VectorizerRemarks remarks = capture_vectorizer_remarks(kHexroomPath);
    REQUIRE(remarks.captured);
    for (const char* kernel : {"generate", "intersect", "shade", "shadow", "accumulate"}) {
        INFO(kernel);
        CHECK_FALSE(remarks.of_kernel(kernel).empty());
        // Vectorised, or a stated reason why not: the verdict a guard tests.
        CHECK((remarks.vectorized(kernel) ||
               !remarks.matching(kernel, "loop not vectorized").empty()));
    }
    CHECK(remarks.of_kernel("no_such_kernel").empty());
    for (const char* stage : {"intersect", "shadow"}) {
        INFO(stage << "'s loop vectoriser remarks:\n" << verdicts(remarks, stage));
        CHECK(remarks.vectorized(stage));
    }
}

TEST_CASE("The check reads each stage's own remarks: the general intersect stage, whose loop "
          "count is not a constant, is not vectorised",
          "[kernels][vectorise]") {
    if (!test_device_is_pocl()) {
        WARN("skipped: the tests do not run on PoCL, whose vectoriser this reads");
        return;
    }
    const VectorizerRemarks remarks =
        capture_vectorizer_remarks(kHexroomPath, "--general --launch-plan stages");
    REQUIRE(remarks.captured);
    INFO("intersect's loop vectoriser remarks:\n" << verdicts(remarks, "intersect"));
    CHECK_FALSE(remarks.matching("intersect", "loop not vectorized").empty());
    CHECK_FALSE(remarks.vectorized("intersect"));
}

} // namespace wp::test
