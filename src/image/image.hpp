// A linear RGB float image: the renderer's output before any view transform.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "util/one_line.hpp"

namespace wp {

// Thrown for malformed image files and images that cannot be encoded; one-line
// message naming the file and the problem. A file that cannot be opened, read
// or written throws FileError (util/file.hpp). Messages can quote the file (a
// header token, a channel name, tinyexr's words), so the constructor passes them
// through one_line (util/one_line.hpp): control characters and invalid UTF-8
// become '?'.
class ImageError : public std::runtime_error {
  public:
    explicit ImageError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

// Name and text pairs about how an image was made, in order.
using Metadata = std::vector<std::pair<std::string, std::string>>;

struct Image {
    int width = 0;
    int height = 0;
    // Row-major, top row first, 3 floats (r, g, b) per pixel: linear radiance.
    std::vector<float> rgb;
    // How the image was made (app/render_metadata.hpp: the version, the
    // scene, the samples per pixel of a render cut short...). EXR files keep
    // it as string attributes, PNG files as text chunks (png_text.hpp); PFM
    // has no place for it.
    Metadata metadata;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.0f) {}

    float* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
    const float* pixel(int x, int y) const {
        return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    }

    // True when the dimensions are non-negative and rgb holds exactly width * height * 3
    // floats, i.e. when indexing through pixel() stays inside the buffer.
    bool has_valid_shape() const noexcept {
        return width >= 0 && height >= 0 &&
               rgb.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
    }
};

// What an image file says about itself, read without decoding its pixels.
struct ImageSummary {
    std::string format; // "OpenEXR", "PNG", "PFM"
    int width = 0;
    int height = 0;
    bool has_metadata_place = true; // false for PFM
    Metadata metadata;
};

// Throws ImageError("<context>: ...") unless the image has a valid shape and, when
// require_pixels is set, at least one pixel. Every function that walks rgb calls this
// first, so a mis-sized buffer is a clear error instead of an out-of-bounds read.
inline void check_image_shape(const Image& img, const std::string& context,
                              bool require_pixels = true) {
    if (!img.has_valid_shape()) {
        throw ImageError(context + ": image is " + std::to_string(img.width) + "x" +
                         std::to_string(img.height) + " but holds " +
                         std::to_string(img.rgb.size()) + " floats");
    }
    if (require_pixels && (img.width == 0 || img.height == 0)) {
        throw ImageError(context + ": image is empty (" + std::to_string(img.width) + "x" +
                         std::to_string(img.height) + ")");
    }
}

} // namespace wp
