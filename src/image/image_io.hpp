// Format-independent image files: the format follows the file extension.
#pragma once

#include "image/image.hpp"
#include "image/tonemap.hpp"

#include <filesystem>

namespace wp {

// Writes .exr or .pfm (lossless linear floats) or .png (8-bit, tone mapped with view);
// the extension is case-insensitive. Any other extension throws ImageError
// "... unsupported image extension '.xyz' (use .exr, .pfm or .png)". Atomic.
void write_image(const std::filesystem::path& path, const Image& img, const ViewOptions& view = {});

// Reads .exr or .pfm (case-insensitive). A missing file throws FileError
// "cannot open '<path>': No such file or directory" (util/file.hpp); a
// malformed one ImageError.
Image read_image(const std::filesystem::path& path);

} // namespace wp
