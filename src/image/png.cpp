#include "image/png.hpp"

#include "image/png_text.hpp"
#include "util/file.hpp"

#include <stb_image_write.h>

#include <climits>
#include <string>
#include <vector>

namespace wp {
namespace {

// stb hands over the encoded PNG in pieces; collect them so that the file can be
// written atomically in one go.
void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

} // namespace

std::vector<unsigned char> encode_png(const Image& img, const ViewOptions& view,
                                      const std::string& context) {
    check_image_shape(img, context);
    // stb_image_write uses int for sizes and strides.
    if (img.width > INT_MAX / 3 || img.height > INT_MAX / (img.width * 3)) {
        throw ImageError(context + ": image too large for PNG encoder");
    }
    const std::vector<std::uint8_t> rgb8 = to_rgb8(img, view);
    std::vector<unsigned char> png;
    if (stbi_write_png_to_func(append_bytes, &png, img.width, img.height, 3, rgb8.data(),
                               img.width * 3) == 0 ||
        png.empty()) {
        throw ImageError(context + ": PNG encoding failed");
    }
    // The metadata, and how this view of the image was made.
    Metadata text = img.metadata;
    text.emplace_back("wavepath.view", describe_view(img, view));
    return add_png_text(png, text, context);
}

void write_png(const std::filesystem::path& path, const Image& img, const ViewOptions& view) {
    const std::vector<unsigned char> png =
        encode_png(img, view, "cannot write '" + path.string() + "'");
    write_bytes_atomically(path, png.data(), png.size());
}

} // namespace wp
