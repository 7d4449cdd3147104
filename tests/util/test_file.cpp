// The file utilities: whole-file reads, atomic replacement (the old file
// survives a failed write and no temp files remain), errno text, extensions.
#include "util/file.hpp"

#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

using wp::FileError;
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
    CHECK_THROWS_AS(wp::write_file_atomically(fresh, [](const fs::path&) { throw 42; }), FileError);
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

TEST_CASE("an unsynced write replaces the file as atomically as a synced one", "[atomic]") {
    TempDir dir;
    const auto path = dir / "entry.bin";
    wp::test::write_text(path, "old");
    wp::write_bytes_atomically(path, "new", 3, wp::Durability::Unsynced);
    CHECK(wp::test::read_text(path) == "new");
    CHECK(dir.entries() == std::vector<std::string>{"entry.bin"});
}

TEST_CASE("read_file_bytes returns exactly the bytes and names the reason it cannot", "[file]") {
    TempDir dir;
    const std::vector<unsigned char> bytes = {0, 1, 255, '\n', 0, 'x'};
    wp::test::write_bytes(dir / "b.bin", bytes);
    CHECK(wp::read_file_bytes(dir / "b.bin") == bytes);
    CHECK(wp::read_file_text(dir / "b.bin") == std::string(bytes.begin(), bytes.end()));
    wp::test::write_bytes(dir / "empty", {});
    CHECK(wp::read_file_bytes(dir / "empty").empty());

    const auto missing = dir / "missing.txt";
    CHECK_THROWS_WITH(wp::read_file_bytes(missing),
                      "cannot open '" + missing.string() + "': No such file or directory");
    try {
        wp::read_file_text(dir.path());
        FAIL("a directory was read");
    } catch (const FileError& e) {
        CHECK(e.reason() == "Is a directory");
        CHECK(std::string(e.what()) == "cannot open '" + dir.path().string() + "': Is a directory");
    }
}

TEST_CASE("errno text, extensions and parent directories", "[file]") {
    CHECK(wp::errno_text(ENOENT) == "No such file or directory");
    CHECK(wp::lower_extension("a/B.EXR") == ".exr");
    CHECK(wp::lower_extension("dir.d/noext") == "");
    CHECK(wp::lower_extension("x.tar.GZ") == ".gz");

    TempDir dir;
    CHECK_NOTHROW(wp::check_parent_directory(dir / "new.png"));
    CHECK_THROWS_WITH(wp::check_parent_directory(dir / "no" / "x.png"),
                      Catch::EndsWith("directory '" + (dir / "no").string() + "' does not exist"));
    wp::test::write_text(dir / "file", "x");
    CHECK_THROWS_WITH(wp::check_parent_directory(dir / "file" / "x.png"),
                      Catch::EndsWith("is not a directory"));
}

TEST_CASE("check_writable refuses what write_file_atomically could not write", "[file]") {
    TempDir dir;
    CHECK_NOTHROW(wp::check_writable(dir / "new.png"));
    CHECK(dir.entries().empty()); // the probe file is gone again
    fs::create_directories(dir / "sub.exr");
    CHECK_THROWS_WITH(wp::check_writable(dir / "sub.exr"),
                      "cannot write '" + (dir / "sub.exr").string() + "': it is a directory");
    // 255 bytes is a valid name, but not once ".tmp-<pid>-<n>" is added.
    std::string name(251, 'x');
    name += ".exr";
    CHECK_THROWS_WITH(wp::check_writable(dir / name), Catch::Contains("file name too long"));
    CHECK_NOTHROW(wp::check_writable(dir / (std::string(200, 'x') + ".exr")));
    CHECK_THROWS_WITH(wp::check_writable(dir / "no" / "x.png"), Catch::Contains("does not exist"));
    // A directory that takes no new files: /sys does not even for root.
    CHECK_THROWS_WITH(wp::check_writable("/sys/x.png"),
                      Catch::Contains("cannot create files in directory '/sys'"));
}

TEST_CASE("resolved_path sees through '..' and symbolic links", "[file]") {
    TempDir dir;
    wp::test::write_text(dir / "a.json", "{}");
    fs::create_directories(dir / "sub");
    fs::create_symlink(dir / "a.json", dir / "link.json");
    const fs::path a = wp::resolved_path(dir / "a.json");
    CHECK(wp::resolved_path(dir / "sub" / ".." / "a.json") == a);
    CHECK(wp::resolved_path(dir / "link.json") == a);
    CHECK(wp::resolved_path(dir / "." / "a.json") == a);
    CHECK(wp::resolved_path(dir / "b.json") != a);
    // Files that do not exist yet resolve as far as their directories do.
    CHECK(wp::resolved_path(dir / "sub" / ".." / "new.exr") == wp::resolved_path(dir / "new.exr"));
}

TEST_CASE("remove_pending_temp_files removes the temporary file of a write in progress",
          "[atomic]") {
    TempDir dir;
    const auto path = dir / "out.exr";
    fs::path seen;
    wp::write_file_atomically(path, [&](const fs::path& temp) {
        seen = temp;
        wp::test::write_text(temp, "partial");
        wp::remove_pending_temp_files(); // what the signal handler does
        CHECK_FALSE(fs::exists(temp));
        wp::test::write_text(temp, "recreated"); // so that the rename can still happen
    });
    CHECK(wp::test::read_text(path) == "recreated");
    // After the write nothing is registered any more.
    wp::test::write_text(seen, "unrelated file with the old temporary name");
    wp::remove_pending_temp_files();
    CHECK(fs::exists(seen));
}
