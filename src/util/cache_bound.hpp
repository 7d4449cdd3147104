// Keeps an on-disk cache below a size by removing its oldest entries first.
//
// A cache here is a directory whose entries (files, or directories taken as
// one unit) can each be rebuilt when missing: wavepath's program cache (one
// file per program) and PoCL's kernel cache (a directory per program, two
// levels down). Without a bound both grow with every new build option,
// driver version or scene feature set, for ever.
#pragma once

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
};

struct CachePruning {
    std::uint64_t bytes_before = 0;
    std::uint64_t bytes_removed = 0;
    std::size_t entries_removed = 0;
};

// Removes the least recently written entries of `dir` until the others
// total at most bound.max_bytes. Names starting with '.' (temporary files of
// writes in progress, util/file.hpp) are never removed nor counted; an entry
// that cannot be removed (another process's, or just gone) is skipped. A
// missing directory is an empty cache. Never throws.
CachePruning bound_cache(const std::filesystem::path& dir, const CacheBound& bound);

} // namespace wp
