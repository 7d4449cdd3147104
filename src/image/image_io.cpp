#include "image/image_io.hpp"

#include "image/exr.hpp"
#include "image/pfm.hpp"
#include "image/png.hpp"
#include "image/png_text.hpp"

#include <string>

#include "util/file.hpp"

namespace wp {

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

ImageSummary read_image_summary(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".exr")
        return read_exr_summary(path);
    if (ext == ".png")
        return read_png_summary(read_file_bytes(path), "cannot read '" + path.string() + "'");
    if (ext == ".pfm") {
        const Image image = read_pfm(path);
        ImageSummary summary;
        summary.format = "PFM";
        summary.width = image.width;
        summary.height = image.height;
        summary.has_metadata_place = false;
        return summary;
    }
    throw ImageError("cannot read '" + path.string() + "': unsupported image extension '" +
                     path.extension().string() + "' (use .exr, .png or .pfm)");
}

} // namespace wp
