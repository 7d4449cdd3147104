// Replace a file atomically: readers (and a crash halfway through a write) see either
// the old complete file or the new complete file, never a partial one.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>

namespace wp {

// Calls write(temp) with a fresh, empty file in the same directory as path (same
// directory, so the final rename stays on one filesystem and is atomic), flushes it to
// disk and renames it over path. If the writer throws or any step fails, the temporary
// file is removed, whatever was at path before is left untouched, and an ImageError
// "cannot write '<path>': <reason>" is thrown.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& temp)>& write);

// write_file_atomically with a writer that stores the given bytes; for encoders that
// produce the whole file in memory (EXR, PFM, PNG).
void write_bytes_atomically(const std::filesystem::path& path, const void* data, std::size_t size);

} // namespace wp
