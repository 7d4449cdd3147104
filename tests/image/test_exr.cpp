// EXR: bit-exact round trips, channel order as other readers see it, half and RGBA
// input, and rejection of truncated or non-RGB files.
#include "image/exr.hpp"

#include "support/temp_dir.hpp"
#include "test_images.hpp"

#include <catch2/catch.hpp>

#include <tinyexr.h> // only to write and inspect files independently of wp::write_exr

#include <cstdlib>
#include <string>
#include <vector>

using wp::Image;
using wp::ImageError;
using wp::test::TempDir;

TEST_CASE("EXR round trip is bit-exact and keeps orientation and channel order", "[exr]") {
    TempDir dir;
    // 37x21 spans two ZIP blocks of 16 scanlines, with a partial last block.
    for (const Image& original : {wp::test::tricky_image(), wp::test::distinct_image(37, 21)}) {
        wp::write_exr(dir / "a.exr", original);
        const Image back = wp::read_exr(dir / "a.exr");
        CHECK(back.width == original.width);
        CHECK(back.height == original.height);
        CHECK(wp::test::bit_identical(back, original));
    }
    CHECK(dir.entries() == std::vector<std::string>{"a.exr"});
}

TEST_CASE("EXR files hold float B, G, R channels that tinyexr's own loader reads as RGB", "[exr]") {
    TempDir dir;
    const Image original = wp::test::distinct_image(3, 2);
    const std::string path = (dir / "c.exr").string();
    wp::write_exr(path, original);

    EXRVersion version;
    REQUIRE(ParseEXRVersionFromFile(&version, path.c_str()) == TINYEXR_SUCCESS);
    EXRHeader header;
    InitEXRHeader(&header);
    const char* err = nullptr;
    REQUIRE(ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err) == TINYEXR_SUCCESS);
    REQUIRE(header.num_channels == 3);
    CHECK(std::string(header.channels[0].name) == "B");
    CHECK(std::string(header.channels[1].name) == "G");
    CHECK(std::string(header.channels[2].name) == "R");
    for (int c = 0; c < 3; ++c) {
        CHECK(header.pixel_types[c] == TINYEXR_PIXELTYPE_FLOAT);
    }
    CHECK(header.data_window.min_x == 0);
    CHECK(header.data_window.max_x == 2);
    CHECK(header.data_window.max_y == 1);
    FreeEXRHeader(&header);

    // LoadEXR looks channels up by name and returns RGBA, top row first.
    float* rgba = nullptr;
    int w = 0;
    int h = 0;
    REQUIRE(LoadEXR(&rgba, &w, &h, path.c_str(), &err) == TINYEXR_SUCCESS);
    REQUIRE(w == 3);
    REQUIRE(h == 2);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) {
                CHECK(rgba[(y * w + x) * 4 + c] == original.pixel(x, y)[c]);
            }
        }
    }
    std::free(rgba);
}

TEST_CASE("read_exr accepts half-float RGBA files and ignores alpha", "[exr]") {
    TempDir dir;
    const std::string path = (dir / "half.exr").string();
    // Values exactly representable in half precision.
    const std::vector<float> rgba = {0.5f, 1.25f, -2.0f, 0.75f, 3.0f, 0.0f, 1024.0f, 1.0f};
    REQUIRE(SaveEXR(rgba.data(), 2, 1, 4, /*save_as_fp16=*/1, path.c_str(), nullptr) ==
            TINYEXR_SUCCESS);
    const Image img = wp::read_exr(path);
    REQUIRE(img.width == 2);
    REQUIRE(img.height == 1);
    CHECK(img.rgb == std::vector<float>{0.5f, 1.25f, -2.0f, 3.0f, 0.0f, 1024.0f});
}

TEST_CASE("read_exr rejects a file without R, G and B channels", "[exr]") {
    TempDir dir;
    const std::string path = (dir / "gray.exr").string();
    const std::vector<float> gray = {0.25f, 0.5f};
    REQUIRE(SaveEXR(gray.data(), 2, 1, 1, 0, path.c_str(), nullptr) == TINYEXR_SUCCESS);
    CHECK_THROWS_WITH(wp::read_exr(path),
                      "cannot read '" + path + "': not an RGB EXR (channels: A)");
}

TEST_CASE("read_exr rejects every truncation of a valid file", "[exr]") {
    TempDir dir;
    const auto path = dir / "t.exr";
    wp::write_exr(path, wp::test::distinct_image(5, 20)); // two ZIP blocks
    const std::vector<unsigned char> full = wp::test::read_bytes(path);
    REQUIRE(full.size() > 100);
    for (std::size_t size = 0; size < full.size(); ++size) {
        wp::test::write_bytes(path, {full.begin(), full.begin() + static_cast<long>(size)});
        INFO("truncated to " << size << " of " << full.size() << " bytes");
        CHECK_THROWS_AS(wp::read_exr(path), ImageError);
        CHECK_THROWS_WITH(wp::read_exr(path), Catch::StartsWith("cannot read '" + path.string()));
    }
    wp::test::write_bytes(path, {full.begin(), full.end() - 1});
    CHECK_THROWS_WITH(wp::read_exr(path), Catch::Contains("truncated EXR file"));
}

TEST_CASE("read_exr rejects files that are not EXR and reports missing files", "[exr]") {
    TempDir dir;
    const auto path = dir / "fake.exr";
    wp::test::write_text(path, "PF\n1 1\n-1.0\n............");
    CHECK_THROWS_WITH(wp::read_exr(path), Catch::Contains("not an OpenEXR file"));
    const auto missing = dir / "missing.exr";
    CHECK_THROWS_WITH(wp::read_exr(missing),
                      "cannot open '" + missing.string() + "': No such file or directory");
}

TEST_CASE("EXR metadata: string attributes read back with or without the pixels", "[exr]") {
    TempDir dir;
    Image img(5, 2);
    img.metadata = {{"wavepath.seed", "9"}, {"wavepath.scene", "sc\xc3\xa8ne.json"}};
    wp::write_exr(dir / "m.exr", img);
    CHECK(wp::read_exr(dir / "m.exr").metadata == img.metadata);
    const wp::ImageSummary summary = wp::read_exr_summary(dir / "m.exr");
    CHECK(summary.format == "OpenEXR");
    CHECK(summary.width == 5);
    CHECK(summary.height == 2);
    CHECK(summary.metadata == img.metadata);
    wp::write_exr(dir / "none.exr", Image(1, 1));
    CHECK(wp::read_exr_summary(dir / "none.exr").metadata.empty());
}
