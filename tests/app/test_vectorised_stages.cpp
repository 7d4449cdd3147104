// PoCL's work-group vectoriser must vectorise the tracing stages of a small
// scene's specialised program: that is most of their speed (3-4x,
// docs/specialization.md), and it holds only while no vector-typed
// instruction or unconvertible branch appears anywhere in the stage's body
// (kernels/traverse.h), which any later edit could break without changing a
// single result.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>

#include "support/vectorizer_remarks.hpp"

namespace wp::test {
namespace {

const std::string kHexroomPath = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";

bool vectorised(const std::string& remarks) {
    return remarks.find("vectorized loop") != std::string::npos;
}

// The loop vectoriser's verdicts among a stage's remarks, for a failure message.
std::string verdicts(const std::string& remarks) {
    std::istringstream lines(remarks);
    std::string line, out;
    while (std::getline(lines, line))
        if (line.find("vectorized loop") != std::string::npos ||
            line.find("loop not vectorized") != std::string::npos)
            out += line + '\n';
    return out;
}

} // namespace

TEST_CASE("The hexroom's specialised intersect and shadow stages are vectorised",
          "[cli][vectorise]") {
    if (!test_device_is_pocl()) {
        WARN("skipped: the tests do not run on PoCL, whose vectoriser this reads");
        return;
    }
    for (const char* stage : {"intersect", "shadow"}) {
        const std::string remarks = vectorizer_remarks_for(kHexroomPath, stage);
        INFO(stage << "'s loop vectoriser remarks:\n" << verdicts(remarks));
        CHECK(vectorised(remarks));
    }
}

TEST_CASE("The check reads each stage's own remarks: the general intersect stage, whose loop "
          "count is not a constant, is not vectorised",
          "[cli][vectorise]") {
    if (!test_device_is_pocl()) {
        WARN("skipped: the tests do not run on PoCL, whose vectoriser this reads");
        return;
    }
    const std::string remarks = vectorizer_remarks_for(kHexroomPath, "intersect", "--general");
    INFO("intersect's loop vectoriser remarks:\n" << verdicts(remarks));
    CHECK(remarks.find("loop not vectorized") != std::string::npos);
    CHECK_FALSE(vectorised(remarks));
}

} // namespace wp::test
