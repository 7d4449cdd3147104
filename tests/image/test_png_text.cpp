// Text chunks in PNG files: the CRC against published values, chunks written
// by hand (their CRCs from zlib) read back, the render's metadata written and
// read back, and files that stay decodable.
#include "image/png.hpp"
#include "image/png_text.hpp"

#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <cstring>
#include <string>
#include <vector>

using wp::Image;
using wp::Metadata;
using wp::test::TempDir;

namespace {

std::vector<unsigned char> bytes_of(const std::string& text) {
    return {text.begin(), text.end()};
}

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data),
                static_cast<unsigned char*>(data) + size);
}

// A 2x1 PNG from stb_image_write alone: no text chunk.
std::vector<unsigned char> plain_png() {
    const unsigned char pixels[6] = {10, 20, 30, 200, 100, 0};
    std::vector<unsigned char> out;
    REQUIRE(stbi_write_png_to_func(append_bytes, &out, 2, 1, 3, pixels, 6) != 0);
    return out;
}

// png with `chunk` (length, type, data and CRC, all given) spliced in after IHDR.
std::vector<unsigned char> with_chunk(std::vector<unsigned char> png,
                                      const std::vector<unsigned char>& chunk) {
    png.insert(png.begin() + 33, chunk.begin(), chunk.end());
    return png;
}

// Decodes with stb_image; empty when it fails.
std::vector<unsigned char> decode(const std::vector<unsigned char>& png, int& w, int& h) {
    int channels = 0;
    unsigned char* pixels =
        stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
    if (pixels == nullptr)
        return {};
    std::vector<unsigned char> out(pixels, pixels + w * h * 3);
    stbi_image_free(pixels);
    return out;
}

} // namespace

TEST_CASE("png_crc32 matches the published check values", "[png_text]") {
    const std::vector<unsigned char> check = bytes_of("123456789");
    CHECK(wp::png_crc32(check.data(), check.size()) == 0xcbf43926u); // the CRC-32 check value
    const std::vector<unsigned char> iend = bytes_of("IEND");
    CHECK(wp::png_crc32(iend.data(), iend.size()) == 0xae426082u); // every PNG's last 4 bytes
    CHECK(wp::png_crc32(nullptr, 0) == 0u);
}

TEST_CASE("text chunks written by hand are read back", "[png_text]") {
    // tEXt "Title" = "Hello"; CRC from Python's zlib.crc32(b'tEXtTitle\x00Hello').
    std::vector<unsigned char> text_chunk = {0,   0,   0,   11,   't',  'E',  'X', 't',
                                             'T', 'i', 't', 'l',  'e',  0,    'H', 'e',
                                             'l', 'l', 'o', 0xcd, 0xcf, 0xc0, 0xcf};
    // iTXt "Author" = "Grüße" (UTF-8), not compressed, no language; CRC from
    // zlib.crc32(b'iTXtAuthor\x00\x00\x00\x00\x00' + 'Grüße'.encode()).
    std::vector<unsigned char> itext = bytes_of("iTXtAuthor");
    itext.insert(itext.end(), {0, 0, 0, 0, 0});
    const std::string gruesse = "Gr\xc3\xbc\xc3\x9f"
                                "e";
    itext.insert(itext.end(), gruesse.begin(), gruesse.end());
    std::vector<unsigned char> itext_chunk = {0, 0, 0,
                                              static_cast<unsigned char>(itext.size() - 4)};
    itext_chunk.insert(itext_chunk.end(), itext.begin(), itext.end());
    itext_chunk.insert(itext_chunk.end(), {0x15, 0x57, 0xa7, 0x4c});

    const std::vector<unsigned char> png =
        with_chunk(with_chunk(plain_png(), itext_chunk), text_chunk);
    const wp::ImageSummary summary = wp::read_png_summary(png, "test");
    CHECK(summary.format == "PNG");
    CHECK(summary.width == 2);
    CHECK(summary.height == 1);
    CHECK(summary.metadata == Metadata{{"Title", "Hello"}, {"Author", gruesse}});
    // The writer makes the same bytes for the same entry.
    CHECK(wp::add_png_text(plain_png(), {{"Title", "Hello"}}, "test") ==
          with_chunk(plain_png(), text_chunk));
    CHECK(wp::add_png_text(plain_png(), {{"Author", gruesse}}, "test") ==
          with_chunk(plain_png(), itext_chunk));

    // One wrong bit in the CRC is an error naming the chunk.
    text_chunk.back() ^= 1;
    CHECK_THROWS_WITH(wp::read_png_summary(with_chunk(plain_png(), text_chunk), "cannot read 'x'"),
                      "cannot read 'x': corrupt PNG file (chunk 'tEXt' has a wrong CRC)");
}

TEST_CASE("write_png stores the metadata and the view, and stays decodable", "[png_text]") {
    TempDir dir;
    Image img(4, 3);
    for (std::size_t i = 0; i < img.rgb.size(); ++i)
        img.rgb[i] = static_cast<float>(i % 7) / 3.0f;
    img.metadata = {{"wavepath.seed", "42"},
                    {"wavepath.scene", "sc\xc3\xa8nes/room.json"},
                    {"wavepath.note", "two\nlines"}};
    const wp::ViewOptions view = wp::ViewOptions::fixed(-1.0);
    wp::write_png(dir / "m.png", img, view);
    const std::vector<unsigned char> file = wp::test::read_bytes(dir / "m.png");
    // Every chunk's CRC is checked, stb's own (IHDR, IDAT, IEND) included.
    const wp::ImageSummary summary = wp::read_png_summary(file, "test");
    CHECK(summary.width == 4);
    CHECK(summary.height == 3);
    Metadata expected = img.metadata;
    expected.emplace_back("wavepath.view", "srgb, exposure -1 stops (fixed)");
    CHECK(summary.metadata == expected);
    int w = 0, h = 0;
    const std::vector<unsigned char> pixels = decode(file, w, h);
    CHECK(w == 4);
    CHECK(h == 3);
    CHECK(pixels == wp::to_rgb8(img, view));
}

TEST_CASE("bad metadata names and damaged PNG files are clear errors", "[png_text]") {
    TempDir dir;
    Image img(1, 1);
    for (const std::string& name : {std::string(), std::string(" lead"), std::string("a  b"),
                                    std::string(80, 'k'), std::string("tab\there")}) {
        INFO("name '" << name << "'");
        img.metadata = {{name, "x"}};
        CHECK_THROWS_AS(wp::write_png(dir / "bad.png", img), wp::ImageError);
    }
    img.metadata = {{"ok", std::string("a\0b", 3)}};
    CHECK_THROWS_WITH(wp::write_png(dir / "bad.png", img),
                      Catch::Contains("metadata 'ok' holds a NUL character"));
    CHECK(dir.entries().empty()); // nothing half-written

    const std::vector<unsigned char> png = plain_png();
    CHECK_THROWS_WITH(wp::read_png_summary(bytes_of("GIF89a"), "r"),
                      "r: not a PNG file (no PNG signature)");
    const std::vector<unsigned char> cut(png.begin(), png.end() - 5);
    CHECK_THROWS_WITH(wp::read_png_summary(cut, "r"), Catch::StartsWith("r: truncated PNG file"));
    CHECK_THROWS_AS(
        wp::add_png_text(bytes_of("not a png at all, but long enough to look at"), {}, "w"),
        wp::ImageError);
}
