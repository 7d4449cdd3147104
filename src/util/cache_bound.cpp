#include "util/cache_bound.hpp"

#include <algorithm>
#include <system_error>
#include <vector>

namespace wp {
namespace {

namespace fs = std::filesystem;

struct Entry {
    fs::path path;
    fs::file_time_type written;
    std::uint64_t bytes = 0;
};

bool hidden(const fs::path& path) {
    const std::string name = path.filename().string();
    return !name.empty() && name[0] == '.';
}

// Bytes of a file, or of every file under a directory; when it was last
// written: the newest time of the entry and anything inside it, since a
// directory's own time changes only when its direct children do.
void measure(Entry& entry) {
    std::error_code ec;
    entry.written = fs::last_write_time(entry.path, ec);
    if (!fs::is_directory(entry.path, ec)) {
        const auto size = fs::file_size(entry.path, ec);
        entry.bytes = ec ? 0 : size;
        return;
    }
    for (auto it = fs::recursive_directory_iterator(
             entry.path, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        std::error_code item_ec;
        const auto time = it->last_write_time(item_ec);
        if (!item_ec)
            entry.written = std::max(entry.written, time);
        if (it->is_regular_file(item_ec)) {
            const auto size = it->file_size(item_ec);
            entry.bytes += item_ec ? 0 : size;
        }
    }
}

void collect(const fs::path& dir, int depth, const CacheBound& bound, std::vector<Entry>& out) {
    std::error_code ec;
    for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        const fs::path& path = it->path();
        if (hidden(path))
            continue;
        if (depth > 1) {
            std::error_code dir_ec;
            if (it->is_directory(dir_ec))
                collect(path, depth - 1, bound, out);
            continue;
        }
        const std::string name = path.filename().string();
        if (!bound.suffix.empty() && (name.size() < bound.suffix.size() ||
                                      name.compare(name.size() - bound.suffix.size(),
                                                   bound.suffix.size(), bound.suffix) != 0))
            continue;
        Entry entry{path, {}, 0};
        measure(entry);
        out.push_back(std::move(entry));
    }
}

std::size_t remove_stale(const fs::path& dir, const CacheBound& bound) {
    if (bound.stale_prefix.empty())
        return 0;
    const auto cutoff = fs::file_time_type::clock::now() - bound.stale_after;
    std::size_t removed = 0;
    std::error_code ec;
    for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        if (it->path().filename().string().rfind(bound.stale_prefix, 0) != 0)
            continue;
        std::error_code item_ec;
        if (!it->is_regular_file(item_ec) || item_ec)
            continue;
        const auto written = it->last_write_time(item_ec);
        if (item_ec || written > cutoff)
            continue;
        if (fs::remove(it->path(), item_ec) && !item_ec)
            ++removed;
    }
    return removed;
}

} // namespace

CachePruning bound_cache(const fs::path& dir, const CacheBound& bound) {
    CachePruning result;
    try {
        result.stale_removed = remove_stale(dir, bound);
        std::vector<Entry> entries;
        collect(dir, std::max(bound.depth, 1), bound, entries);
        for (const Entry& e : entries)
            result.bytes_before += e.bytes;
        std::sort(entries.begin(), entries.end(),
                  [](const Entry& a, const Entry& b) { return a.written < b.written; });
        std::uint64_t total = result.bytes_before;
        for (const Entry& e : entries) {
            if (total <= bound.max_bytes)
                break;
            std::error_code ec;
            fs::remove_all(e.path, ec);
            if (ec)
                continue;
            total -= e.bytes;
            result.bytes_removed += e.bytes;
            ++result.entries_removed;
        }
    } catch (const std::exception&) {
        // A cache that cannot be pruned is only a bigger cache.
    }
    return result;
}

} // namespace wp
