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

// The format, size and metadata of an .exr, .png or .pfm file (case-insensitive),
// without decoding the pixels of an .exr or .png. PFM has no place for metadata:
// its summary says so (has_metadata_place false). Errors as read_image's.
ImageSummary read_image_summary(const std::filesystem::path& path);

} // namespace wp
