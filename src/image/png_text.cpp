#include "image/png_text.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace wp {
namespace {

constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
// A chunk: 4-byte length, 4-byte type, the data, 4-byte CRC of type and data.
constexpr std::size_t kChunkOverhead = 12;
constexpr std::uint32_t kMaxChunkLength = 0x7fffffff; // PNG's limit (2^31 - 1)

std::uint32_t load_be32(const unsigned char* p) {
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 |
           std::uint32_t{p[3]};
}

void append_be32(std::vector<unsigned char>& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<unsigned char>(v >> shift));
}

void append_chunk(std::vector<unsigned char>& out, const char* type,
                  const std::vector<unsigned char>& data) {
    append_be32(out, static_cast<std::uint32_t>(data.size()));
    const std::size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    append_be32(out, png_crc32(out.data() + start, out.size() - start));
}

// PNG's keyword rules (PNG specification, 11.3.4.2).
bool valid_keyword(const std::string& name) {
    if (name.empty() || name.size() > 79 || name.front() == ' ' || name.back() == ' ' ||
        name.find("  ") != std::string::npos)
        return false;
    return std::all_of(name.begin(), name.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return (u >= 32 && u <= 126) || u >= 161;
    });
}

bool is_ascii(const std::string& text) {
    return std::all_of(text.begin(), text.end(),
                       [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

// Latin-1 bytes (tEXt) as UTF-8.
std::string latin1_to_utf8(const unsigned char* p, std::size_t size) {
    std::string out;
    for (std::size_t i = 0; i < size; ++i) {
        if (p[i] < 0x80) {
            out += static_cast<char>(p[i]);
        } else {
            out += static_cast<char>(0xc0 | (p[i] >> 6));
            out += static_cast<char>(0x80 | (p[i] & 0x3f));
        }
    }
    return out;
}

// The entry a text chunk holds; false for one too malformed to read (no
// keyword terminator).
bool parse_text_chunk(const std::string& type, const unsigned char* data, std::size_t size,
                      std::pair<std::string, std::string>& entry) {
    const auto* end = data + size;
    const auto* nul = std::find(data, end, 0);
    if (nul == end)
        return false;
    entry.first = latin1_to_utf8(data, static_cast<std::size_t>(nul - data));
    const unsigned char* rest = nul + 1;
    if (type == "tEXt") {
        entry.second = latin1_to_utf8(rest, static_cast<std::size_t>(end - rest));
        return true;
    }
    if (type == "zTXt") {
        entry.second = "(compressed text, not read)";
        return true;
    }
    // iTXt: compression flag, method, language tag NUL, translated keyword NUL, text.
    if (end - rest < 2)
        return false;
    const bool compressed = rest[0] != 0;
    const auto* language_end = std::find(rest + 2, end, 0);
    if (language_end == end)
        return false;
    const auto* translated_end = std::find(language_end + 1, end, 0);
    if (translated_end == end)
        return false;
    entry.second =
        compressed ? "(compressed text, not read)" : std::string(translated_end + 1, end);
    return true;
}

} // namespace

std::uint32_t png_crc32(const unsigned char* data, std::size_t size) {
    // The reflected polynomial 0xedb88320, a byte at a time from a table.
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k)
                c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xffffffffu;
    for (std::size_t i = 0; i < size; ++i)
        c = table[(c ^ data[i]) & 0xff] ^ (c >> 8);
    return c ^ 0xffffffffu;
}

std::vector<unsigned char> add_png_text(const std::vector<unsigned char>& png,
                                        const Metadata& entries, const std::string& context) {
    const std::size_t header_end = kSignature.size() + kChunkOverhead + 13;
    if (png.size() < header_end || !std::equal(kSignature.begin(), kSignature.end(), png.begin()) ||
        std::memcmp(png.data() + 12, "IHDR", 4) != 0)
        throw ImageError(context + ": not a PNG starting with IHDR");
    std::vector<unsigned char> chunks;
    for (const auto& [name, text] : entries) {
        if (!valid_keyword(name))
            throw ImageError(context + ": metadata name '" + name.substr(0, 80) +
                             "' is not a PNG keyword (1 to 79 printable characters, no leading, "
                             "trailing or double spaces)");
        if (text.find('\0') != std::string::npos)
            throw ImageError(context + ": metadata '" + name + "' holds a NUL character");
        if (name.size() + text.size() + 5 > kMaxChunkLength)
            throw ImageError(context + ": metadata '" + name + "' is too long for a PNG chunk");
        std::vector<unsigned char> data(name.begin(), name.end());
        data.push_back(0);
        if (is_ascii(text)) {
            data.insert(data.end(), text.begin(), text.end());
            append_chunk(chunks, "tEXt", data);
        } else {
            // Not compressed, no language tag, no translated keyword; UTF-8 text.
            data.insert(data.end(), {0, 0, 0, 0});
            data.insert(data.end(), text.begin(), text.end());
            append_chunk(chunks, "iTXt", data);
        }
    }
    std::vector<unsigned char> out = png;
    out.insert(out.begin() + static_cast<std::ptrdiff_t>(header_end), chunks.begin(), chunks.end());
    return out;
}

ImageSummary read_png_summary(const std::vector<unsigned char>& png, const std::string& context) {
    if (png.size() < kSignature.size() ||
        !std::equal(kSignature.begin(), kSignature.end(), png.begin()))
        throw ImageError(context + ": not a PNG file (no PNG signature)");
    ImageSummary summary;
    summary.format = "PNG";
    std::size_t offset = kSignature.size();
    bool first = true;
    while (true) {
        if (png.size() - offset < kChunkOverhead)
            throw ImageError(context + ": truncated PNG file (no IEND chunk)");
        const std::uint32_t length = load_be32(png.data() + offset);
        const std::string type(reinterpret_cast<const char*>(png.data() + offset + 4), 4);
        if (length > kMaxChunkLength || length > png.size() - offset - kChunkOverhead)
            throw ImageError(context + ": truncated PNG file (chunk '" + type +
                             "' ends past the end of the file)");
        const unsigned char* data = png.data() + offset + 8;
        const std::uint32_t stored = load_be32(data + length);
        if (png_crc32(png.data() + offset + 4, length + 4) != stored)
            throw ImageError(context + ": corrupt PNG file (chunk '" + type + "' has a wrong CRC)");
        if (first) {
            if (type != "IHDR" || length != 13)
                throw ImageError(context + ": corrupt PNG file (the first chunk is not IHDR)");
            summary.width = static_cast<int>(load_be32(data));
            summary.height = static_cast<int>(load_be32(data + 4));
            first = false;
        }
        if (type == "tEXt" || type == "zTXt" || type == "iTXt") {
            std::pair<std::string, std::string> entry;
            if (parse_text_chunk(type, data, length, entry))
                summary.metadata.push_back(entry);
        }
        if (type == "IEND")
            return summary;
        offset += kChunkOverhead + length;
    }
}

} // namespace wp
