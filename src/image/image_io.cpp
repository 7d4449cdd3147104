#include "image/image_io.hpp"

#include "image/exr.hpp"
#include "image/pfm.hpp"
#include "image/png.hpp"

#include <cctype>
#include <string>

namespace wp {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return ext;
}

} // namespace

void write_image(const std::filesystem::path& path, const Image& img, const ViewOptions& view) {
    const std::string ext = lower_extension(path);
    if (ext == ".exr") {
        write_exr(path, img);
    } else if (ext == ".pfm") {
        write_pfm(path, img);
    } else if (ext == ".png") {
        write_png(path, img, view);
    } else {
        throw ImageError("cannot write '" + path.string() + "': unsupported image extension '" +
                         path.extension().string() + "' (use .exr, .pfm or .png)");
    }
}

Image read_image(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".exr") {
        return read_exr(path);
    }
    if (ext == ".pfm") {
        return read_pfm(path);
    }
    throw ImageError("cannot read '" + path.string() + "': unsupported image extension '" +
                     path.extension().string() + "' (use .exr or .pfm)");
}

} // namespace wp
