// The fuzzers' findings, kept as regression tests (docs/fuzzing.md). Every input
// a fuzz target (fuzz/) crashed on, hung on or rejected with an unclean message
// is saved as tests/data/fuzz/<target>/<name>, and tests/data/fuzz/expected.txt
// says what it must give now that the bug is fixed:
//
//   <target>/<name> | ok                      read without error
//   <target>/<name> | <the exact message>     rejected with this error
//
// The tests feed each input through the target's own entry point (with the
// fuzzer's names: "fuzz.obj", "fuzz.ply", "fuzz.json", "fuzz-input") and check
// the outcome and that every message is clean (fuzz/clean_error.hpp, the
// fuzzers' own check).
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "../../fuzz/clean_error.hpp"

namespace fuzz_regressions {

inline std::filesystem::path data_dir() {
    return std::filesystem::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "fuzz";
}

struct Case {
    std::string name; // "<target>/<file>", as expected.txt lists it
    std::string bytes;
    std::string expected; // "ok" or the exact message
};

inline std::string read_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The cases of one target. Fails unless expected.txt and the folder list the
// same inputs, so that no saved input goes untested.
inline std::vector<Case> cases(const std::string& target) {
    std::ifstream manifest(data_dir() / "expected.txt");
    REQUIRE(manifest);
    std::vector<Case> found;
    std::set<std::string> listed;
    for (std::string line; std::getline(manifest, line);) {
        if (line.empty() || line[0] == '#')
            continue;
        const auto bar = line.find(" | ");
        REQUIRE(bar != std::string::npos);
        const std::string name = line.substr(0, bar);
        if (name.rfind(target + "/", 0) != 0)
            continue;
        listed.insert(name);
        found.push_back({name, read_bytes(data_dir() / name), line.substr(bar + 3)});
    }
    std::set<std::string> on_disk;
    if (std::filesystem::is_directory(data_dir() / target))
        for (const auto& entry : std::filesystem::directory_iterator(data_dir() / target))
            on_disk.insert(target + "/" + entry.path().filename().string());
    CHECK(on_disk == listed);
    return found;
}

// Checks the message of an outcome against the case: "ok" for success (an
// empty message), else the exact error, which must be clean.
inline void check_outcome(const Case& c, const std::string& error) {
    INFO(c.name);
    if (c.expected == "ok") {
        CHECK(error.empty());
        return;
    }
    CHECK(error == c.expected);
    CHECK(wp::fuzz::message_problem(error).empty());
}

} // namespace fuzz_regressions
