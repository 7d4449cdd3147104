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

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

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
    // A directory cannot be renamed over a file: the writer leaves one
    // where the temporary file was.
    const auto path = dir / "taken";
    wp::test::write_text(path, "keep");
    CHECK_THROWS_WITH(wp::write_file_atomically(path,
                                                [](const fs::path& temp) {
                                                    fs::remove(temp);
                                                    fs::create_directory(temp);
                                                }),
                      Catch::StartsWith("cannot write '" + path.string() + "': cannot rename"));
    CHECK(wp::test::read_text(path) == "keep");
    CHECK(dir.entries() == std::vector<std::string>{"taken"});
    // A directory at the path itself is refused before anything is written.
    fs::create_directory(dir / "sub");
    CHECK_THROWS_WITH(wp::write_bytes_atomically(dir / "sub", "data", 4),
                      "cannot write '" + (dir / "sub").string() + "': it is a directory");
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

namespace {

// A character device node in the test's own directory (the number of
// /dev/null, 1:3, or /dev/full, 1:7), never under /dev; false where this
// user may not make one.
bool make_char_device(const fs::path& path, unsigned minor) {
    return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)) == 0;
}

} // namespace

TEST_CASE("an output that is a device or FIFO is written through, never replaced", "[atomic]") {
    TempDir dir;
    const auto null = dir / "null", full = dir / "full";
    if (!make_char_device(null, 3) || !make_char_device(full, 7)) {
        WARN("mknod is not allowed here: " << wp::errno_text(errno));
        return;
    }
    CHECK_NOTHROW(wp::check_writable(null));
    wp::write_bytes_atomically(null, "trace", 5);
    struct stat st {};
    REQUIRE(::stat(null.c_str(), &st) == 0);
    CHECK(S_ISCHR(st.st_mode)); // still the device, not a regular file renamed over it
    CHECK(dir.entries() == std::vector<std::string>{"full", "null"});

    // A device that fails the write fails it with one line, and stays.
    CHECK_THROWS_WITH(wp::write_bytes_atomically(full, "checkpoint", 10),
                      "cannot write '" + full.string() + "': No space left on device");
    REQUIRE(::stat(full.c_str(), &st) == 0);
    CHECK(S_ISCHR(st.st_mode));

    // A FIFO with no reader is refused at once instead of waited on.
    const auto fifo = dir / "fifo";
    REQUIRE(::mkfifo(fifo.c_str(), 0666) == 0);
    CHECK_NOTHROW(wp::check_writable(fifo));
    CHECK_THROWS_WITH(wp::write_bytes_atomically(fifo, "x", 1),
                      "cannot write '" + fifo.string() + "': no process is reading the FIFO");
    REQUIRE(::stat(fifo.c_str(), &st) == 0);
    CHECK(S_ISFIFO(st.st_mode));
    // With a reader, the bytes go through it.
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    REQUIRE(reader >= 0);
    wp::write_bytes_atomically(fifo, "abc", 3);
    char got[8] = {};
    CHECK(::read(reader, got, sizeof got) == 3);
    ::close(reader);
    CHECK(std::string(got) == "abc");
}

TEST_CASE("a read-only output file is refused, not replaced", "[atomic]") {
    TempDir dir;
    const auto path = dir / "theirs.exr";
    wp::test::write_text(path, "someone else's");
    fs::permissions(path, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    const std::string message = "cannot write '" + path.string() +
                                "': the file is read-only (its permissions do not let this user "
                                "write it); remove it or change its mode first";
    CHECK_THROWS_WITH(wp::check_writable(path), message);
    CHECK_THROWS_WITH(wp::write_bytes_atomically(path, "mine", 4), message);
    CHECK(wp::test::read_text(path) == "someone else's");
    CHECK(dir.entries() == std::vector<std::string>{"theirs.exr"});
}

TEST_CASE("read_file_bytes refuses FIFOs and devices without blocking", "[file]") {
    TempDir dir;
    const auto fifo = dir / "scene.json";
    REQUIRE(::mkfifo(fifo.c_str(), 0666) == 0); // no writer: opening it would block
    CHECK_THROWS_WITH(wp::read_file_bytes(fifo),
                      "cannot open '" + fifo.string() + "': it is a FIFO, not a regular file");
    const auto zero = dir / "zero.ply";
    if (::mknod(zero.c_str(), S_IFCHR | 0666, makedev(1, 5)) == 0) // endless, as /dev/zero
        CHECK_THROWS_WITH(wp::read_file_bytes(zero), "cannot open '" + zero.string() +
                                                         "': it is a character device, not a "
                                                         "regular file");
}
