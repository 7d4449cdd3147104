// Reading a whole file into memory, with the error messages the image readers share.
#pragma once

#include <filesystem>
#include <vector>

namespace wp {

// Returns the file's contents. Throws ImageError "cannot open '<path>': <reason>" (for
// example "No such file or directory") or "cannot read '<path>': <reason>". The readers
// decode from memory so that every format reports a missing file the same way.
std::vector<unsigned char> read_file_bytes(const std::filesystem::path& path);

} // namespace wp
