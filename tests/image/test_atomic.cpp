// write_file_atomically: the old file survives a failed write and no temp files remain.
#include "image/atomic_file.hpp"

#include "image/image.hpp"
#include "temp_dir.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

using wp::ImageError;
using wp::test::TempDir;
namespace fs = std::filesystem;

TEST_CASE("write_file_atomically replaces the file and leaves no temp files", "[atomic]") {
    TempDir dir;
    const auto path = dir / "out.txt";
    wp::test::write_text(path, "old");
    fs::path seen_temp;
    wp::write_file_atomically(path, [&](const fs::path& temp) {
        seen_temp = temp;
        CHECK(temp.parent_path() == dir.path()); // same directory: rename stays atomic
        CHECK(temp != path);
        CHECK(fs::exists(temp));
        CHECK(wp::test::read_text(path) == "old"); // untouched while writing
        wp::test::write_text(temp, "new");
    });
    CHECK(wp::test::read_text(path) == "new");
    CHECK(!fs::exists(seen_temp));
    CHECK(dir.entries() == std::vector<std::string>{"out.txt"});

    // A second write gets a different temporary name.
    fs::path second_temp;
    wp::write_bytes_atomically(path, "abc", 3);
    wp::write_file_atomically(path, [&](const fs::path& temp) {
        second_temp = temp;
        wp::test::write_text(temp, "third");
    });
    CHECK(second_temp != seen_temp);
    CHECK(wp::test::read_text(path) == "third");
}

TEST_CASE("a throwing writer leaves the previous file intact and no temp files", "[atomic]") {
    TempDir dir;
    const auto path = dir / "image.exr";
    wp::test::write_text(path, "previous content");
    CHECK_THROWS_WITH(wp::write_file_atomically(path,
                                                [](const fs::path& temp) {
                                                    wp::test::write_text(temp, "partial");
                                                    throw std::runtime_error("disk on fire");
                                                }),
                      "cannot write '" + path.string() + "': disk on fire");
    CHECK(wp::test::read_text(path) == "previous content");
    CHECK(dir.entries() == std::vector<std::string>{"image.exr"});

    // Without a previous file, nothing is created.
    const auto fresh = dir / "fresh.exr";
    CHECK_THROWS_AS(wp::write_file_atomically(fresh, [](const fs::path&) { throw 42; }),
                    ImageError);
    CHECK(!fs::exists(fresh));
    CHECK(dir.entries() == std::vector<std::string>{"image.exr"});
}

TEST_CASE("write_file_atomically reports a missing directory clearly", "[atomic]") {
    TempDir dir;
    const auto path = dir / "no" / "such" / "dir" / "out.png";
    bool called = false;
    CHECK_THROWS_WITH(wp::write_file_atomically(path, [&](const fs::path&) { called = true; }),
                      "cannot write '" + path.string() + "': directory '" +
                          (dir / "no/such/dir").string() + "' does not exist");
    CHECK(!called);

    wp::test::write_text(dir / "file", "x");
    CHECK_THROWS_WITH(wp::write_bytes_atomically(dir / "file" / "out.png", "", 0),
                      Catch::Contains("is not a directory"));
}

TEST_CASE("a failed rename removes the temp file and leaves the target alone", "[atomic]") {
    TempDir dir;
    // A non-empty directory cannot be replaced by a file.
    const auto path = dir / "taken";
    fs::create_directory(path);
    wp::test::write_text(path / "inside", "keep");
    CHECK_THROWS_WITH(wp::write_bytes_atomically(path, "data", 4),
                      Catch::StartsWith("cannot write '" + path.string() + "': cannot rename"));
    CHECK(wp::test::read_text(path / "inside") == "keep");
    CHECK(dir.entries() == std::vector<std::string>{"taken"});
}
