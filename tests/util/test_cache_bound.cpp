// bound_cache: the oldest entries go first, until the rest fit.
#include "util/cache_bound.hpp"

#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <string>

using wp::test::TempDir;
namespace fs = std::filesystem;

namespace {

// A file of `bytes` (sparse: no disk used) written `age` hours ago.
void make(const fs::path& path, std::uintmax_t bytes, int age) {
    fs::create_directories(path.parent_path());
    wp::test::write_text(path, "");
    fs::resize_file(path, bytes);
    fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::hours(age));
}

} // namespace

TEST_CASE("bound_cache removes the oldest files first, until the rest fit", "[cache]") {
    TempDir dir;
    make(dir / "a.clbin", 100, 3); // oldest
    make(dir / "b.clbin", 100, 1);
    make(dir / "c.clbin", 100, 2);
    make(dir / "notes.txt", 1000, 9);        // not an entry: another suffix
    make(dir / ".d.clbin.tmp-1-0", 1000, 9); // a write in progress
    const wp::CachePruning pruned = wp::bound_cache(dir.path(), {250, 1, ".clbin"});
    CHECK(pruned.bytes_before == 300);
    CHECK(pruned.bytes_removed == 100);
    CHECK(pruned.entries_removed == 1);
    CHECK_FALSE(fs::exists(dir / "a.clbin"));
    CHECK(fs::exists(dir / "b.clbin"));
    CHECK(fs::exists(dir / "c.clbin"));
    CHECK(fs::exists(dir / "notes.txt"));
    CHECK(fs::exists(dir / ".d.clbin.tmp-1-0"));

    // Within the bound nothing goes; at 0 every entry does.
    CHECK(wp::bound_cache(dir.path(), {200, 1, ".clbin"}).entries_removed == 0);
    CHECK(wp::bound_cache(dir.path(), {0, 1, ".clbin"}).entries_removed == 2);
    CHECK(fs::exists(dir / "notes.txt"));
}

TEST_CASE("bound_cache takes directories two levels down as units", "[cache]") {
    TempDir dir;
    // PoCL's layout: kcache/XX/HASH/{program.bc, kernel/64-1-1/kernel.so}.
    make(dir / "AA" / "OLD" / "program.bc", 300, 5);
    make(dir / "AA" / "OLD" / "k" / "64-1-1" / "k.so", 300, 5);
    make(dir / "AB" / "NEW" / "program.bc", 300, 5);
    make(dir / "AB" / "NEW" / "k" / "64-1-1" / "k.so", 300, 0); // used just now
    const wp::CachePruning pruned = wp::bound_cache(dir.path(), {1000, 2, ""});
    CHECK(pruned.bytes_before == 1200);
    CHECK(pruned.bytes_removed == 600);
    CHECK_FALSE(fs::exists(dir / "AA" / "OLD"));
    CHECK(fs::exists(dir / "AB" / "NEW" / "k" / "64-1-1" / "k.so"));
}

TEST_CASE("bound_cache of a missing directory does nothing", "[cache]") {
    TempDir dir;
    const wp::CachePruning pruned = wp::bound_cache(dir / "none", {0, 1, ""});
    CHECK(pruned.bytes_before == 0);
    CHECK(pruned.entries_removed == 0);
}
