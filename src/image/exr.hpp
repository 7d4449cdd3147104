// OpenEXR files: the renderer's lossless float output, readable by every image tool.
#pragma once

#include "image/image.hpp"

#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace wp {

// A layer of an EXR beside the image's R, G, B: channels named
// `name.channel` ("albedo.R", "depth.Z"), values interleaved, channels.size()
// per pixel.
struct ExrLayer {
    std::string name;
    std::vector<std::string> channels;
    std::vector<float> values;
};

// Writes a single-part scanline EXR with float32 channels B, G, R and those of
// `layers`, all sorted by name (the order the format requires), ZIP-compressed
// (lossless). Atomic.
void write_exr(const std::filesystem::path& path, const Image& img,
               std::span<const ExrLayer> layers = {});

// Every half or float channel of a single-part scanline EXR by its full
// name ("R", "albedo.G"), as a float plane of width x height values. Errors
// as read_exr's.
std::map<std::string, std::vector<float>> read_exr_channels(const std::filesystem::path& path);

// Reads a single-part scanline EXR with R, G and B channels (an A channel is ignored)
// stored as half or float. The data window becomes the image. Anything else (missing
// channels, tiled, multi-part or deep files, integer channels, corrupt or truncated
// data) is an ImageError naming the file.
Image read_exr(const std::filesystem::path& path);

// The size (of the data window) and string attributes of an EXR file, from
// its header alone. Errors as read_exr's for the header.
ImageSummary read_exr_summary(const std::filesystem::path& path);

// read_exr on a file's bytes already in memory; `file_name` stands for the path in
// messages. The fuzz targets (fuzz/) and their regression tests read through here.
Image decode_exr(std::span<const unsigned char> bytes, const std::string& file_name);

} // namespace wp
