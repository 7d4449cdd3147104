// PFM: bit-exact round trips, the exact byte layout, and strict rejection of bad files.
#include "image/pfm.hpp"

#include "support/temp_dir.hpp"
#include "test_images.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using wp::Image;
using wp::ImageError;
using wp::test::TempDir;

namespace {

std::vector<unsigned char> bytes_of(const std::string& s) {
    return {s.begin(), s.end()};
}

void append(std::vector<unsigned char>& v, std::initializer_list<unsigned char> bytes) {
    v.insert(v.end(), bytes);
}

// A 1x2 image, top pixel (1, 2, -0.5), bottom pixel (0.25, 4, 0), as PFM with the given
// scale line; the float bytes are written out by hand (1.0f = 0x3f800000, ...).
std::vector<unsigned char> hand_built_pfm(bool little_endian) {
    std::vector<unsigned char> v = bytes_of(little_endian ? "PF\n1 2\n-1.0\n" : "PF\n1 2\n1.0\n");
    if (little_endian) {
        // Bottom row first: 0.25, 4.0, 0.0, then the top row: 1.0, 2.0, -0.5.
        append(v, {0x00, 0x00, 0x80, 0x3e, 0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0x00, 0x00});
        append(v, {0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0xbf});
    } else {
        append(v, {0x3e, 0x80, 0x00, 0x00, 0x40, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
        append(v, {0x3f, 0x80, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0xbf, 0x00, 0x00, 0x00});
    }
    return v;
}

Image hand_built_image() {
    Image img(1, 2);
    img.rgb = {1.0f, 2.0f, -0.5f, 0.25f, 4.0f, 0.0f};
    return img;
}

} // namespace

TEST_CASE("PFM round trip is bit-exact and keeps orientation and channel order", "[pfm]") {
    TempDir dir;
    for (const Image& original : {wp::test::distinct_image(4, 3), wp::test::tricky_image()}) {
        wp::write_pfm(dir / "a.pfm", original);
        const Image back = wp::read_pfm(dir / "a.pfm");
        CHECK(back.width == original.width);
        CHECK(back.height == original.height);
        CHECK(wp::test::bit_identical(back, original));
    }
    CHECK(wp::read_pfm(dir / "a.pfm").pixel(1, 1)[0] == std::numeric_limits<float>::denorm_min());
}

TEST_CASE("PFM writer produces the hand-built byte layout (header text, bottom row first)",
          "[pfm]") {
    TempDir dir;
    wp::write_pfm(dir / "h.pfm", hand_built_image());
    CHECK(wp::test::read_bytes(dir / "h.pfm") == hand_built_pfm(true));
}

TEST_CASE("PFM reader decodes hand-built little- and big-endian files", "[pfm]") {
    TempDir dir;
    for (const bool little : {true, false}) {
        wp::test::write_bytes(dir / "h.pfm", hand_built_pfm(little));
        const Image img = wp::read_pfm(dir / "h.pfm");
        INFO("little endian: " << little);
        CHECK(wp::test::bit_identical(img, hand_built_image()));
    }
}

TEST_CASE("PFM reader rejects malformed headers with an error naming the file", "[pfm]") {
    TempDir dir;
    const std::string pixels(12, '\0'); // one pixel's worth of data
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"", "missing 'PF' signature"},
        {"P6\n1 1\n255\n" + pixels, "missing 'PF' signature"},
        {"Pf\n1 1\n-1.0\n" + std::string(4, '\0'), "grayscale"},
        {"PF1 1\n-1.0\n" + pixels, "whitespace after 'PF'"},
        {"PF\n0 1\n-1.0\n", "invalid width '0'"},
        {"PF\n-1 1\n-1.0\n" + pixels, "invalid width '-1'"},
        {"PF\n1 x\n-1.0\n" + pixels, "invalid height 'x'"},
        {"PF\n1 1.5\n-1.0\n" + pixels, "invalid height '1.5'"},
        {"PF\n99999999999 1\n-1.0\n" + pixels, "invalid width"},
        {"PF\n1 1\n0.0\n" + pixels, "invalid scale '0.0'"},
        {"PF\n1 1\nnan\n" + pixels, "invalid scale 'nan'"},
        {"PF\n1 1\n-1.0x\n" + pixels, "invalid scale"},
        {"PF\n1 1\n", "missing scale"},
        {"PF\n1 1\n-1.0", "missing scale"},
        {"PF\n1", "missing width"},
    };
    for (const auto& [content, reason] : cases) {
        INFO("file content: " << content.substr(0, 20));
        const auto path = dir / "bad.pfm";
        wp::test::write_text(path, content);
        CHECK_THROWS_AS(wp::read_pfm(path), ImageError);
        CHECK_THROWS_WITH(wp::read_pfm(path),
                          Catch::StartsWith("cannot read '" + path.string() + "': ") &&
                              Catch::Contains(reason));
    }
}

TEST_CASE("PFM reader rejects truncated pixel data and trailing bytes", "[pfm]") {
    TempDir dir;
    const auto path = dir / "t.pfm";
    wp::write_pfm(path, wp::test::distinct_image(3, 2));
    const std::vector<unsigned char> full = wp::test::read_bytes(path);
    const std::size_t header = std::string("PF\n3 2\n-1.0\n").size();
    REQUIRE(full.size() == header + 3 * 2 * 12);

    // Every cut inside the pixel data, including a missing last byte.
    for (std::size_t size = header; size < full.size(); ++size) {
        wp::test::write_bytes(path, {full.begin(), full.begin() + static_cast<long>(size)});
        INFO("truncated to " << size << " bytes");
        CHECK_THROWS_WITH(wp::read_pfm(path), Catch::Contains("truncated PFM pixel data") &&
                                                  Catch::Contains(path.string()));
    }
    std::vector<unsigned char> longer = full;
    longer.push_back(0);
    wp::test::write_bytes(path, longer);
    CHECK_THROWS_WITH(wp::read_pfm(path), Catch::Contains("1 unexpected bytes"));

    wp::test::write_bytes(path, full);
    CHECK(wp::test::bit_identical(wp::read_pfm(path), wp::test::distinct_image(3, 2)));
}

TEST_CASE("PFM reader reports a missing file like the OS does", "[pfm]") {
    TempDir dir;
    const auto path = dir / "missing.pfm";
    CHECK_THROWS_WITH(wp::read_pfm(path),
                      "cannot open '" + path.string() + "': No such file or directory");
}

TEST_CASE("PFM writer rejects an image whose buffer does not match its size", "[pfm]") {
    TempDir dir;
    Image img(2, 2);
    img.rgb.pop_back();
    CHECK_THROWS_AS(wp::write_pfm(dir / "x.pfm", img), ImageError);
    CHECK_THROWS_WITH(wp::write_pfm(dir / "y.pfm", Image{}), Catch::Contains("empty"));
    CHECK(dir.entries().empty());
}
