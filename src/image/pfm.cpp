#include "image/pfm.hpp"

#include "util/file.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace wp {
namespace {

constexpr std::size_t kBytesPerPixel = 3 * sizeof(float);

bool is_space(unsigned char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

std::uint32_t byteswap32(std::uint32_t v) {
    return (v >> 24) | ((v >> 8) & 0x0000ff00u) | ((v << 8) & 0x00ff0000u) | (v << 24);
}

// Reads a float stored with the given byte order. Going through uint32 and memcpy keeps
// this free of alignment and aliasing problems on any host.
float load_float(const unsigned char* p, bool little_endian) {
    std::uint32_t bits;
    std::memcpy(&bits, p, sizeof bits);
    if (little_endian != (std::endian::native == std::endian::little)) {
        bits = byteswap32(bits);
    }
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

void store_float_le(unsigned char* p, float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    if constexpr (std::endian::native != std::endian::little) {
        bits = byteswap32(bits);
    }
    std::memcpy(p, &bits, sizeof bits);
}

// Tokenizer for the three header fields; every failure names the file.
class HeaderParser {
  public:
    HeaderParser(std::span<const unsigned char> bytes, std::string context)
        : bytes_(bytes), context_(std::move(context)) {}

    [[noreturn]] void fail(const std::string& why) const {
        throw ImageError(context_ + ": " + why);
    }

    void expect_magic() {
        if (bytes_.size() < 2 || bytes_[0] != 'P' || (bytes_[1] != 'F' && bytes_[1] != 'f')) {
            fail("not a PFM file (missing 'PF' signature)");
        }
        if (bytes_[1] == 'f') {
            fail("grayscale PFM ('Pf') is not supported, only colour ('PF')");
        }
        pos_ = 2;
        if (pos_ >= bytes_.size() || !is_space(bytes_[pos_])) {
            fail("malformed PFM header (expected whitespace after 'PF')");
        }
    }

    // Next whitespace-delimited token; it must be followed by a whitespace character
    // because binary data starts right after the header.
    std::string_view token(const char* what) {
        while (pos_ < bytes_.size() && is_space(bytes_[pos_])) {
            ++pos_;
        }
        const std::size_t start = pos_;
        while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) {
            ++pos_;
        }
        if (start == pos_ || pos_ >= bytes_.size()) {
            fail(std::string("truncated PFM header (missing ") + what + ")");
        }
        return {reinterpret_cast<const char*>(bytes_.data()) + start, pos_ - start};
    }

    int dimension(const char* what) {
        const std::string_view t = token(what);
        int value = 0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
        // from_chars accepts a leading '-'; dimensions are plain positive decimals.
        if (ec != std::errc() || end != t.data() + t.size() || t.front() == '-' || value <= 0) {
            fail(std::string("malformed PFM header (invalid ") + what + " '" + std::string(t) +
                 "')");
        }
        return value;
    }

    double scale() {
        const std::string_view t = token("scale");
        double value = 0.0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
        if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(value) ||
            value == 0.0) {
            fail("malformed PFM header (invalid scale '" + std::string(t) + "')");
        }
        // Exactly one whitespace character separates the header from the pixel data.
        ++pos_;
        return value;
    }

    std::size_t position() const { return pos_; }

  private:
    std::span<const unsigned char> bytes_;
    std::string context_;
    std::size_t pos_ = 0;
};

} // namespace

void write_pfm(const std::filesystem::path& path, const Image& img) {
    check_image_shape(img, "cannot write '" + path.string() + "'");
    const std::string header =
        "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
    const std::size_t row_bytes = static_cast<std::size_t>(img.width) * kBytesPerPixel;
    std::vector<unsigned char> bytes(header.size() +
                                     row_bytes * static_cast<std::size_t>(img.height));
    std::memcpy(bytes.data(), header.data(), header.size());
    unsigned char* out = bytes.data() + header.size();
    // PFM stores the bottom row first; Image keeps the top row first.
    for (int y = img.height - 1; y >= 0; --y) {
        const float* row = img.pixel(0, y);
        for (std::size_t i = 0; i < static_cast<std::size_t>(img.width) * 3; ++i) {
            store_float_le(out, row[i]);
            out += sizeof(float);
        }
    }
    write_bytes_atomically(path, bytes.data(), bytes.size());
}

Image read_pfm(const std::filesystem::path& path) {
    return decode_pfm(read_file_bytes(path), path.string());
}

Image decode_pfm(std::span<const unsigned char> bytes, const std::string& file_name) {
    HeaderParser header(bytes, "cannot read '" + file_name + "'");
    header.expect_magic();
    const int width = header.dimension("width");
    const int height = header.dimension("height");
    // The sign gives the byte order; the magnitude is a nominal brightness scale that
    // writers in practice leave at 1, so the stored values are returned unchanged.
    const bool little_endian = header.scale() < 0.0;

    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (pixels > std::numeric_limits<std::size_t>::max() / kBytesPerPixel) {
        header.fail("PFM dimensions " + std::to_string(width) + "x" + std::to_string(height) +
                    " are too large");
    }
    const std::size_t expected = pixels * kBytesPerPixel;
    const std::size_t available = bytes.size() - header.position();
    if (available < expected) {
        header.fail("truncated PFM pixel data (expected " + std::to_string(expected) +
                    " bytes for " + std::to_string(width) + "x" + std::to_string(height) +
                    ", found " + std::to_string(available) + ")");
    }
    if (available > expected) {
        header.fail("PFM file has " + std::to_string(available - expected) +
                    " unexpected bytes after the pixel data (wrong size in header?)");
    }

    Image img(width, height);
    const unsigned char* in = bytes.data() + header.position();
    for (int y = height - 1; y >= 0; --y) {
        float* row = img.pixel(0, y);
        for (std::size_t i = 0; i < static_cast<std::size_t>(width) * 3; ++i) {
            row[i] = load_float(in, little_endian);
            in += sizeof(float);
        }
    }
    return img;
}

} // namespace wp
