// A linear RGB float image: the renderer's output before any view transform.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace wp {

// Thrown for unreadable, unwritable or malformed image files; one-line message
// naming the file and the problem.
class ImageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct Image {
    int width = 0;
    int height = 0;
    // Row-major, top row first, 3 floats (r, g, b) per pixel: linear radiance.
    std::vector<float> rgb;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.0f) {}

    float* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
    const float* pixel(int x, int y) const {
        return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    }
};

} // namespace wp
