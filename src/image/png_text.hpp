// Text in PNG files: the metadata of a render as text chunks, which
// stb_image_write (the encoder) does not write. They are inserted into the
// encoded file after its header chunk; PNG's chunk format is simple enough
// that this is a few lines, where libpng would be a second encoder and a new
// dependency for the same bytes.
#pragma once

#include "image/image.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace wp {

// The CRC-32 every PNG chunk ends with (ISO 3309, the polynomial zlib and
// Ethernet use), of the chunk's type and data.
std::uint32_t png_crc32(const unsigned char* data, std::size_t size);

// png with one text chunk per entry inserted after IHDR: tEXt where the text
// is ASCII, iTXt (UTF-8) otherwise. Throws ImageError (after context) for a
// name PNG does not allow as a keyword (1 to 79 printable Latin-1
// characters, no leading, trailing or double spaces), a text holding a NUL,
// or png not starting with a PNG signature and IHDR.
std::vector<unsigned char> add_png_text(const std::vector<unsigned char>& png,
                                        const Metadata& entries, const std::string& context);

// The size and text of an encoded PNG: the text is the tEXt and uncompressed
// iTXt chunks in file order, as UTF-8 (tEXt is Latin-1); zTXt and compressed
// iTXt chunks are listed with the text "(compressed text, not read)".
// Walks every chunk, checking its CRC. Throws
// ImageError (after context) for a missing signature, a truncated chunk, a
// wrong CRC or a file without IHDR first or without IEND.
ImageSummary read_png_summary(const std::vector<unsigned char>& png, const std::string& context);

} // namespace wp
