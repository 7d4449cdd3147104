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
    const wp::CachePruning pruned = wp::bound_cache(dir.path(), {250, 1, ".clbin", "", {}});
    CHECK(pruned.bytes_before == 300);
    CHECK(pruned.bytes_removed == 100);
    CHECK(pruned.entries_removed == 1);
    CHECK_FALSE(fs::exists(dir / "a.clbin"));
    CHECK(fs::exists(dir / "b.clbin"));
    CHECK(fs::exists(dir / "c.clbin"));
    CHECK(fs::exists(dir / "notes.txt"));
    CHECK(fs::exists(dir / ".d.clbin.tmp-1-0"));

    // Within the bound nothing goes; at 0 every entry does.
    CHECK(wp::bound_cache(dir.path(), {200, 1, ".clbin", "", {}}).entries_removed == 0);
    CHECK(wp::bound_cache(dir.path(), {0, 1, ".clbin", "", {}}).entries_removed == 2);
    CHECK(fs::exists(dir / "notes.txt"));
}

TEST_CASE("bound_cache takes directories two levels down as units", "[cache]") {
    TempDir dir;
    // PoCL's layout: kcache/XX/HASH/{program.bc, kernel/64-1-1/kernel.so}.
    make(dir / "AA" / "OLD" / "program.bc", 300, 5);
    make(dir / "AA" / "OLD" / "k" / "64-1-1" / "k.so", 300, 5);
    make(dir / "AB" / "NEW" / "program.bc", 300, 5);
    make(dir / "AB" / "NEW" / "k" / "64-1-1" / "k.so", 300, 0); // used just now
    const wp::CachePruning pruned = wp::bound_cache(dir.path(), {1000, 2, "", "", {}});
    CHECK(pruned.bytes_before == 1200);
    CHECK(pruned.bytes_removed == 600);
    CHECK_FALSE(fs::exists(dir / "AA" / "OLD"));
    CHECK(fs::exists(dir / "AB" / "NEW" / "k" / "64-1-1" / "k.so"));
}

TEST_CASE("bound_cache of a missing directory does nothing", "[cache]") {
    TempDir dir;
    const wp::CachePruning pruned = wp::bound_cache(dir / "none", {0, 1, "", "", {}});
    CHECK(pruned.bytes_before == 0);
    CHECK(pruned.entries_removed == 0);
}

TEST_CASE("bound_cache removes old files of the stale prefix, not recent ones", "[cache]") {
    // PoCL leaves empty "tempfile_XXXXXX" files beside its kcache entries.
    TempDir dir;
    make(dir / "tempfile_OLD123", 0, 2);
    make(dir / "tempfile_NEW456", 0, 0); // a compile may be writing it now
    make(dir / "AA" / "HASH" / "program.bc", 100, 2);
    make(dir / "AA" / "tempfile_deep", 0, 2); // only the directory's own children
    const wp::CacheBound bound{1000, 2, "", "tempfile_", std::chrono::hours(1)};
    const wp::CachePruning pruned = wp::bound_cache(dir.path(), bound);
    CHECK(pruned.stale_removed == 1);
    CHECK(pruned.entries_removed == 0);
    CHECK_FALSE(fs::exists(dir / "tempfile_OLD123"));
    CHECK(fs::exists(dir / "tempfile_NEW456"));
    CHECK(fs::exists(dir / "AA" / "HASH" / "program.bc"));
    // Without a prefix nothing stale is looked for.
    make(dir / "tempfile_OLD789", 0, 2);
    CHECK(wp::bound_cache(dir.path(), {1000, 2, "", "", {}}).stale_removed == 0);
    CHECK(fs::exists(dir / "tempfile_OLD789"));
}
