// PNG previews: 8-bit sRGB images for viewing, never for measuring (use EXR/PFM).
#pragma once

#include "image/image.hpp"
#include "image/tonemap.hpp"

#include <filesystem>

namespace wp {

// Tone maps img with view (see to_rgb8) and writes an 8-bit RGB PNG with
// img.metadata, and "wavepath.view" (describe_view), as text chunks. Atomic.
void write_png(const std::filesystem::path& path, const Image& img, const ViewOptions& view = {});

} // namespace wp
