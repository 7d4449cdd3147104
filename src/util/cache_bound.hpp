// Keeps an on-disk cache below a size by removing its oldest entries first.
//
// A cache here is a directory whose entries (files, or directories taken as
// one unit) can each be rebuilt when missing: wavepath's program cache (one
// file per program) and PoCL's kernel cache (a directory per program, two
// levels down). Without a bound both grow with every new build option,
// driver version or scene feature set, for ever.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>

namespace wp {

struct CacheBound {
    std::uint64_t max_bytes = 0;
    // How deep the entries are: 1 for the directory's own children, 2 for
    // its grandchildren (PoCL's kcache/XX/HASH/).
    int depth = 1;
    // Only entries whose name ends so (e.g. ".clbin"); empty: every entry.
    std::string suffix;
    // Files directly in the directory whose name starts so and that were
    // last written longer than stale_after ago are removed, whatever the
    // size: PoCL makes "tempfile_XXXXXX" files there and leaves some behind,
    // empty, for ever. A compile may still be writing a recent one, so only
    // old ones go. Empty: none.
    std::string stale_prefix;
    std::chrono::seconds stale_after{0};
};

struct CachePruning {
    std::uint64_t bytes_before = 0;
    std::uint64_t bytes_removed = 0;
    std::size_t entries_removed = 0;
    std::size_t stale_removed = 0; // stale_prefix files
};

// Removes the least recently written entries of `dir` until the others
// total at most bound.max_bytes. Names starting with '.' (temporary files of
// writes in progress, util/file.hpp) are never removed nor counted; an entry
// that cannot be removed (another process's, or just gone) is skipped. A
// missing directory is an empty cache. First, the stale files that
// bound.stale_prefix names are removed. Never throws.
CachePruning bound_cache(const std::filesystem::path& dir, const CacheBound& bound);

} // namespace wp
