// PNG previews: 8-bit sRGB images for viewing, never for measuring (use EXR/PFM).
#pragma once

#include "image/image.hpp"
#include "image/tonemap.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wp {

// Tone maps img with view (see to_rgb8) and writes an 8-bit RGB PNG with
// img.metadata, and "wavepath.view" (describe_view), as text chunks. Atomic.
void write_png(const std::filesystem::path& path, const Image& img, const ViewOptions& view = {});

// The same PNG file's bytes (text chunks included), in memory (for the live preview, app/preview_server.hpp).
// Errors throw ImageError starting with `context`.
std::vector<unsigned char> encode_png(const Image& img, const ViewOptions& view = {},
                                      const std::string& context = "cannot encode PNG");

} // namespace wp
