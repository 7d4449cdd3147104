// Portable float map (PFM) files: the simplest lossless float format, easy to inspect
// and to load from Python or other renderers when comparing results.
#pragma once

#include "image/image.hpp"

#include <filesystem>
#include <span>
#include <string>

namespace wp {

// Writes a colour ("PF") little-endian PFM: header "PF\n<w> <h>\n-1.0\n", then float32
// r, g, b per pixel with rows stored bottom-to-top as the format requires. Atomic.
void write_pfm(const std::filesystem::path& path, const Image& img);

// Reads a colour PFM of either byte order (the sign of the scale) and returns it top row
// first. Strict: a malformed header, a grayscale "Pf" file, or pixel data shorter or
// longer than width * height * 12 bytes is an ImageError naming the file.
Image read_pfm(const std::filesystem::path& path);

// read_pfm on a file's bytes already in memory; `file_name` stands for the path in
// messages. The fuzz targets (fuzz/) and their regression tests read through here.
Image decode_pfm(std::span<const unsigned char> bytes, const std::string& file_name);

} // namespace wp
