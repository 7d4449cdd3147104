#include "image/exr.hpp"

#include "util/file.hpp"

#include <tinyexr.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace wp {
namespace {

// tinyexr reports errors as malloc'd C strings; turn one into a message and free it.
std::string take_error(const char* err, const char* fallback) {
    if (err == nullptr) {
        return fallback;
    }
    std::string msg(err);
    FreeEXRErrorMessage(err);
    // tinyexr messages often end with a newline; keep ours to one line.
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) {
        msg.pop_back();
    }
    for (char& c : msg) {
        if (c == '\n') {
            c = ' ';
        }
    }
    return msg.empty() ? std::string(fallback) : msg;
}

// ParseEXRHeaderFromMemory fills the header even when it fails, so it is always freed.
struct HeaderGuard {
    EXRHeader header;
    HeaderGuard() { InitEXRHeader(&header); }
    ~HeaderGuard() { FreeEXRHeader(&header); }
    HeaderGuard(const HeaderGuard&) = delete;
    HeaderGuard& operator=(const HeaderGuard&) = delete;
};

// Only armed after a successful load: tinyexr already frees the image when decoding
// fails, and FreeEXRImage does not reset its pointers, so freeing again would double free.
struct ImageGuard {
    EXRImage image;
    bool loaded = false;
    ImageGuard() { InitEXRImage(&image); }
    ~ImageGuard() {
        if (loaded) {
            FreeEXRImage(&image);
        }
    }
    ImageGuard(const ImageGuard&) = delete;
    ImageGuard& operator=(const ImageGuard&) = delete;
};

std::uint64_t load_le(const unsigned char* p, int bytes) {
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) {
        v = (v << 8) | p[i];
    }
    return v;
}

// Throws unless a PIZ chunk's own lengths stay inside the chunk. tinyexr 1.0.1's
// PIZ decoder trusts them: it copies the bitmap range [min, max] and reads the
// Huffman length and the Huffman header after it without comparing with the
// chunk's size, so a damaged chunk makes it read up to 8 KiB past the end of
// the file's buffer (found by exr_fuzzer under AddressSanitizer). `chunk` is
// the chunk's data after its line number and length; a chunk as long as its
// raw pixels is stored uncompressed, which tinyexr copies as it is.
void check_piz_chunk(std::span<const unsigned char> chunk, std::int64_t line,
                     const EXRHeader& header, const std::string& where) {
    const std::int64_t end_line = std::min<std::int64_t>(line + 32, header.data_window.max_y + 1);
    std::int64_t pixel_bytes = 0;
    for (int c = 0; c < header.num_channels; ++c)
        pixel_bytes += header.channels[c].pixel_type == TINYEXR_PIXELTYPE_HALF ? 2 : 4;
    const std::int64_t width =
        static_cast<std::int64_t>(header.data_window.max_x) - header.data_window.min_x + 1;
    if (end_line <= line ||
        static_cast<std::int64_t>(chunk.size()) == width * (end_line - line) * pixel_bytes)
        return; // no lines (tinyexr rejects the chunk before decoding) or stored raw
    const std::uint64_t size = chunk.size();
    std::uint64_t at = 4; // past the bitmap's first and last byte index
    if (size >= 4) {
        const std::uint64_t first = load_le(chunk.data(), 2), last = load_le(chunk.data() + 2, 2);
        if (first <= last)
            at += last - first + 1;
    }
    // The Huffman data: its length, then at least its 20-byte header.
    const std::uint64_t length = size >= at + 4 ? load_le(chunk.data() + at, 4) : 0;
    if (size < at + 4 || length < 20 || length > size - at - 4)
        throw ImageError(where + " is a corrupt PIZ chunk (its lengths reach past its end)");
}

// Checks that every chunk listed in the offset table lies inside the file. tinyexr
// 1.0.1 detects a cut-off chunk too, but only after allocating the channel buffers,
// which it then leaks; checking first avoids that for the common damage (a truncated
// file) and gives a clearer message. Mirrors tinyexr's block count for scanline files.
void check_chunks_complete(std::span<const unsigned char> bytes, const EXRHeader& header,
                           const std::string& context) {
    const std::uint64_t size = bytes.size();
    const std::uint64_t table = 8 + static_cast<std::uint64_t>(header.header_len);
    std::uint64_t blocks = 0;
    if (header.chunk_count > 0) {
        blocks = static_cast<std::uint64_t>(header.chunk_count);
    } else {
        const int lines = header.compression_type == TINYEXR_COMPRESSIONTYPE_ZIP   ? 16
                          : header.compression_type == TINYEXR_COMPRESSIONTYPE_PIZ ? 32
                          : header.compression_type == TINYEXR_COMPRESSIONTYPE_ZFP ? 16
                                                                                   : 1;
        const std::int64_t height =
            static_cast<std::int64_t>(header.data_window.max_y) - header.data_window.min_y + 1;
        if (height <= 0) {
            throw ImageError(context + ": invalid EXR data window");
        }
        blocks = (static_cast<std::uint64_t>(height) + lines - 1) / lines;
    }
    if (table > size || blocks > (size - table) / 8) {
        throw ImageError(context + ": truncated EXR file (offset table incomplete)");
    }
    for (std::uint64_t i = 0; i < blocks; ++i) {
        const std::uint64_t offset = load_le(bytes.data() + table + i * 8, 8);
        const bool piz = header.compression_type == TINYEXR_COMPRESSIONTYPE_PIZ;
        if (offset == 0) {
            // An incomplete table, which tinyexr rebuilds by scanning; let it
            // decide, except for PIZ, whose chunks must all be checked first.
            if (piz)
                throw ImageError(context + ": PIZ-compressed EXR file with an incomplete offset "
                                           "table (damaged or truncated)");
            return;
        }
        const bool header_fits = offset <= size && size - offset >= 8;
        const std::uint64_t data_len = header_fits ? load_le(bytes.data() + offset + 4, 4) : 0;
        if (!header_fits || data_len > size - offset - 8) {
            throw ImageError(context + ": truncated EXR file (chunk " + std::to_string(i + 1) +
                             " of " + std::to_string(blocks) + " ends past the end of the file)");
        }
        if (piz)
            check_piz_chunk(bytes.subspan(offset + 8, data_len),
                            static_cast<std::int32_t>(load_le(bytes.data() + offset, 4)), header,
                            context + ": chunk " + std::to_string(i + 1) + " of " +
                                std::to_string(blocks));
    }
}

// Throws unless the data window's width and height are positive and fit an
// int. tinyexr 1.0.1 computes them as max - min + 1 in int, which overflows
// (undefined behaviour) for a window such as x in [-2^31, 4]: found by
// exr_fuzzer under UndefinedBehaviorSanitizer. No such window is an image.
void check_data_window(const EXRBox2i& w, const std::string& context) {
    const std::int64_t width = static_cast<std::int64_t>(w.max_x) - w.min_x + 1;
    const std::int64_t height = static_cast<std::int64_t>(w.max_y) - w.min_y + 1;
    const std::int64_t limit = std::numeric_limits<int>::max();
    if (width <= 0 || height <= 0 || width > limit || height > limit)
        throw ImageError(context + ": invalid EXR data window (" + std::to_string(w.min_x) + ", " +
                         std::to_string(w.min_y) + ") to (" + std::to_string(w.max_x) + ", " +
                         std::to_string(w.max_y) + ")");
}

struct MallocFree {
    void operator()(unsigned char* p) const noexcept { std::free(p); }
};

// The string attributes of a parsed header: the metadata write_exr wrote.
Metadata string_attributes(const EXRHeader& header) {
    Metadata metadata;
    for (int a = 0; a < header.num_custom_attributes; ++a) {
        const EXRAttribute& attribute = header.custom_attributes[a];
        if (std::string(attribute.type) == "string" && attribute.value != nullptr &&
            attribute.size >= 0)
            metadata.emplace_back(attribute.name,
                                  std::string(reinterpret_cast<const char*>(attribute.value),
                                              static_cast<std::size_t>(attribute.size)));
    }
    return metadata;
}

// Checks the version and parses the header of the EXR file in bytes.
void parse_header(std::span<const unsigned char> bytes, HeaderGuard& header,
                  const std::string& context) {
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS) {
        throw ImageError(context + ": not an OpenEXR file");
    }
    if (version.multipart || version.non_image) {
        throw ImageError(context + ": multi-part and deep EXR files are not supported");
    }
    if (version.tiled) {
        throw ImageError(context + ": tiled EXR files are not supported");
    }

    const char* err = nullptr;
    if (ParseEXRHeaderFromMemory(&header.header, &version, bytes.data(), bytes.size(), &err) !=
        TINYEXR_SUCCESS) {
        throw ImageError(context + ": invalid EXR header: " + take_error(err, "unknown error"));
    }
    if (header.header.tiled) {
        throw ImageError(context + ": tiled EXR files are not supported");
    }
}

} // namespace

void write_exr(const std::filesystem::path& path, const Image& img,
               std::span<const ExrLayer> layers) {
    const std::string context = "cannot write '" + path.string() + "'";
    check_image_shape(img, context);

    // EXR stores channels planar and sorted by name: one plane per channel,
    // R, G, B from the image and each layer's, then sorted.
    const std::size_t n =
        static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height);
    struct Plane {
        std::string name;
        std::vector<float> values;
    };
    std::vector<Plane> planes;
    for (std::size_t c = 0; c < 3; ++c) {
        Plane plane{std::string(1, "RGB"[c]), std::vector<float>(n)};
        for (std::size_t i = 0; i < n; ++i)
            plane.values[i] = img.rgb[i * 3 + c];
        planes.push_back(std::move(plane));
    }
    for (const ExrLayer& layer : layers) {
        const std::size_t k = layer.channels.size();
        if (k == 0 || layer.values.size() != n * k)
            throw ImageError(context + ": layer '" + layer.name + "' has " +
                             std::to_string(layer.values.size()) + " values, not " +
                             std::to_string(n) + " pixels of " + std::to_string(k) + " channels");
        for (std::size_t c = 0; c < k; ++c) {
            Plane plane{layer.name + "." + layer.channels[c], std::vector<float>(n)};
            for (std::size_t i = 0; i < n; ++i)
                plane.values[i] = layer.values[i * k + c];
            planes.push_back(std::move(plane));
        }
    }
    std::sort(planes.begin(), planes.end(),
              [](const Plane& a, const Plane& b) { return a.name < b.name; });
    const std::size_t count = planes.size();
    std::vector<unsigned char*> plane_ptrs(count);
    // The header's arrays are ours (not malloc'd), so FreeEXRHeader must not see them.
    std::vector<EXRChannelInfo> channels(count);
    for (std::size_t c = 0; c < count; ++c) {
        if (planes[c].name.size() >= sizeof channels[c].name ||
            (c > 0 && planes[c].name == planes[c - 1].name))
            throw ImageError(context + ": channel name '" + planes[c].name +
                             "' is too long or repeated");
        plane_ptrs[c] = reinterpret_cast<unsigned char*>(planes[c].values.data());
        std::strncpy(channels[c].name, planes[c].name.c_str(), sizeof channels[c].name - 1);
    }

    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = static_cast<int>(count);
    image.width = img.width;
    image.height = img.height;
    image.images = plane_ptrs.data();

    std::vector<int> pixel_types(count, TINYEXR_PIXELTYPE_FLOAT);
    std::vector<int> requested_types = pixel_types; // store float32: no precision loss
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = static_cast<int>(count);
    header.channels = channels.data();
    header.pixel_types = pixel_types.data();
    header.requested_pixel_types = requested_types.data();
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    // The metadata as string attributes: the value is the text's bytes, no terminator.
    std::vector<EXRAttribute> attributes;
    for (const auto& [name, text] : img.metadata) {
        if (name.empty() || name.size() >= sizeof(EXRAttribute::name) ||
            text.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
            throw ImageError(context + ": metadata name '" + name.substr(0, 40) +
                             "' is empty or too long");
        EXRAttribute attribute{};
        std::strncpy(attribute.name, name.c_str(), sizeof attribute.name - 1);
        std::strncpy(attribute.type, "string", sizeof attribute.type - 1);
        attribute.value =
            reinterpret_cast<unsigned char*>(const_cast<char*>(text.data())); // only read
        attribute.size = static_cast<int>(text.size());
        attributes.push_back(attribute);
    }
    if (attributes.size() > TINYEXR_MAX_CUSTOM_ATTRIBUTES)
        throw ImageError(context + ": more than " + std::to_string(TINYEXR_MAX_CUSTOM_ATTRIBUTES) +
                         " metadata entries");
    header.num_custom_attributes = static_cast<int>(attributes.size());
    header.custom_attributes = attributes.empty() ? nullptr : attributes.data();

    // Encode in memory, then write atomically: tinyexr's own file writer would truncate
    // the previous image before the new one is complete.
    unsigned char* memory = nullptr;
    const char* err = nullptr;
    const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
    std::unique_ptr<unsigned char, MallocFree> owned(memory);
    if (size == 0 || memory == nullptr) {
        throw ImageError(context +
                         ": EXR encoding failed: " + take_error(err, "unknown tinyexr error"));
    }
    write_bytes_atomically(path, memory, size);
}

ImageSummary read_exr_summary(const std::filesystem::path& path) {
    const std::string context = "cannot read '" + path.string() + "'";
    HeaderGuard header;
    parse_header(read_file_bytes(path), header, context);
    ImageSummary summary;
    summary.format = "OpenEXR";
    const EXRBox2i& window = header.header.data_window;
    check_data_window(window, context);
    summary.width = window.max_x - window.min_x + 1;
    summary.height = window.max_y - window.min_y + 1;
    summary.metadata = string_attributes(header.header);
    return summary;
}

Image read_exr(const std::filesystem::path& path) {
    return decode_exr(read_file_bytes(path), path.string());
}

Image decode_exr(std::span<const unsigned char> bytes, const std::string& file_name) {
    const std::string context = "cannot read '" + file_name + "'";
    HeaderGuard header;
    parse_header(bytes, header, context);
    const char* err = nullptr;

    // Find R, G and B; ask tinyexr to convert half channels to float while decoding.
    int channel_index[3] = {-1, -1, -1};
    std::string found;
    for (int c = 0; c < header.header.num_channels; ++c) {
        const EXRChannelInfo& info = header.header.channels[c];
        const std::string name = info.name;
        found += (found.empty() ? "" : ",") + name;
        const int slot = name == "R" ? 0 : name == "G" ? 1 : name == "B" ? 2 : -1;
        if (slot < 0) {
            continue;
        }
        const int type = header.header.pixel_types[c];
        if (type != TINYEXR_PIXELTYPE_HALF && type != TINYEXR_PIXELTYPE_FLOAT) {
            throw ImageError(context + ": channel '" + name +
                             "' holds integers; only half or float channels are supported");
        }
        if (info.x_sampling != 1 || info.y_sampling != 1) {
            throw ImageError(context + ": channel '" + name + "' is subsampled");
        }
        header.header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
        channel_index[slot] = c;
    }
    if (channel_index[0] < 0 || channel_index[1] < 0 || channel_index[2] < 0) {
        throw ImageError(context + ": not an RGB EXR (channels: " +
                         (found.empty() ? std::string("none") : found) + ")");
    }

    check_data_window(header.header.data_window, context);
    check_chunks_complete(bytes, header.header, context);

    ImageGuard image;
    // tinyexr 1.0.1 sets the image's channel count only once every chunk has
    // decoded; when one fails, its cleanup (FreeEXRImage) frees the channel
    // pointer array but, seeing no channels, none of the channel buffers, and
    // those leak. With the count set first, the same cleanup frees them too:
    // the image has exactly the header's channels.
    image.image.num_channels = header.header.num_channels;
    err = nullptr;
    if (LoadEXRImageFromMemory(&image.image, &header.header, bytes.data(), bytes.size(), &err) !=
        TINYEXR_SUCCESS) {
        throw ImageError(context +
                         ": corrupt or truncated EXR data: " + take_error(err, "unknown error"));
    }
    image.loaded = true;
    if (image.image.images == nullptr || image.image.width <= 0 || image.image.height <= 0) {
        throw ImageError(context + ": EXR file holds no scanline pixels");
    }

    Image img(image.image.width, image.image.height);
    const std::size_t n =
        static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height);
    for (int slot = 0; slot < 3; ++slot) {
        const float* plane =
            reinterpret_cast<const float*>(image.image.images[channel_index[slot]]);
        for (std::size_t i = 0; i < n; ++i) {
            img.rgb[i * 3 + static_cast<std::size_t>(slot)] = plane[i];
        }
    }
    img.metadata = string_attributes(header.header);
    return img;
}

} // namespace wp

namespace wp {

std::map<std::string, std::vector<float>> read_exr_channels(const std::filesystem::path& path) {
    const std::string context = "cannot read '" + path.string() + "'";
    const std::vector<unsigned char> bytes = read_file_bytes(path);
    HeaderGuard header;
    parse_header(bytes, header, context);
    for (int c = 0; c < header.header.num_channels; ++c) {
        const int type = header.header.pixel_types[c];
        if (type != TINYEXR_PIXELTYPE_HALF && type != TINYEXR_PIXELTYPE_FLOAT)
            throw ImageError(context + ": channel '" + header.header.channels[c].name +
                             "' holds integers; only half or float channels are supported");
        header.header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    }
    check_data_window(header.header.data_window, context);
    check_chunks_complete(bytes, header.header, context);
    ImageGuard image;
    image.image.num_channels = header.header.num_channels; // as decode_exr says why
    const char* err = nullptr;
    if (LoadEXRImageFromMemory(&image.image, &header.header, bytes.data(), bytes.size(), &err) !=
        TINYEXR_SUCCESS)
        throw ImageError(context +
                         ": corrupt or truncated EXR data: " + take_error(err, "unknown error"));
    image.loaded = true;
    if (image.image.images == nullptr || image.image.width <= 0 || image.image.height <= 0)
        throw ImageError(context + ": EXR file holds no scanline pixels");
    const std::size_t n =
        static_cast<std::size_t>(image.image.width) * static_cast<std::size_t>(image.image.height);
    std::map<std::string, std::vector<float>> channels;
    for (int c = 0; c < header.header.num_channels; ++c) {
        const float* plane = reinterpret_cast<const float*>(image.image.images[c]);
        channels[header.header.channels[c].name] = std::vector<float>(plane, plane + n);
    }
    return channels;
}

} // namespace wp
