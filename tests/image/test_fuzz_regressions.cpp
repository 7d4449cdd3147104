// The image fuzzers' findings (tests/support/fuzz_regressions.hpp), and the
// in-memory entry points they read through, decode_exr and decode_pfm, checked
// against read_exr and read_pfm on the same files.
#include <catch2/catch.hpp>

#include <filesystem>
#include <span>
#include <string>

#include "image/exr.hpp"
#include "image/pfm.hpp"
#include "support/fuzz_regressions.hpp"
#include "support/temp_dir.hpp"
#include "test_images.hpp"

#include <tinyexr.h> // to write PIZ files independently of wp::write_exr

#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

template <typename Decode> void check_image_cases(const std::string& target, Decode decode) {
    for (const auto& c : fuzz_regressions::cases(target)) {
        std::string error;
        try {
            const wp::Image image = decode(
                std::span(reinterpret_cast<const unsigned char*>(c.bytes.data()), c.bytes.size()),
                "fuzz-input");
            CHECK(image.has_valid_shape());
        } catch (const wp::ImageError& e) {
            error = e.what();
        }
        fuzz_regressions::check_outcome(c, error);
    }
}

std::span<const unsigned char> as_bytes(const std::string& s) {
    return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

} // namespace

// The image as tinyexr writes it with PIZ compression and float or half channels.
std::string piz_exr(const wp::Image& img, int pixel_type) {
    const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
    std::vector<std::vector<float>> planes(3, std::vector<float>(n)); // B, G, R
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            planes[static_cast<std::size_t>(c)][i] =
                img.rgb[i * 3 + static_cast<std::size_t>(2 - c)];
    unsigned char* pointers[3] = {reinterpret_cast<unsigned char*>(planes[0].data()),
                                  reinterpret_cast<unsigned char*>(planes[1].data()),
                                  reinterpret_cast<unsigned char*>(planes[2].data())};
    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = 3;
    image.width = img.width;
    image.height = img.height;
    image.images = pointers;
    EXRChannelInfo channels[3] = {};
    std::strcpy(channels[0].name, "B");
    std::strcpy(channels[1].name, "G");
    std::strcpy(channels[2].name, "R");
    int input_types[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT,
                          TINYEXR_PIXELTYPE_FLOAT};
    int stored_types[3] = {pixel_type, pixel_type, pixel_type};
    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = 3;
    header.channels = channels;
    header.pixel_types = input_types;
    header.requested_pixel_types = stored_types;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_PIZ;
    unsigned char* memory = nullptr;
    const char* err = nullptr;
    const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
    REQUIRE(size > 0);
    std::string bytes(reinterpret_cast<const char*>(memory), size);
    std::free(memory);
    return bytes;
}

// Under AddressSanitizer (the CI's sanitizer build) the leak this input found in
// tinyexr's failure path fails the test when the process exits.
TEST_CASE("fuzz regressions: EXR inputs give clean errors", "[fuzz][exr]") {
    check_image_cases("exr", [](std::span<const unsigned char> bytes, const std::string& name) {
        return wp::decode_exr(bytes, name);
    });
}

// The check of PIZ chunks (against a heap over-read that exr_fuzzer found in
// tinyexr's PIZ decoder) passes every chunk tinyexr writes: compressed ones,
// a last block of fewer than 32 lines, and chunks stored raw.
TEST_CASE("PIZ files as tinyexr writes them are read back", "[fuzz][exr]") {
    for (const auto& [w, h] : {std::pair{37, 70}, std::pair{3, 1}, std::pair{64, 32}}) {
        const wp::Image original = wp::test::distinct_image(w, h);
        for (int type : {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_HALF}) {
            INFO(w << "x" << h << " type " << type);
            const std::string bytes = piz_exr(original, type);
            const wp::Image back = wp::decode_exr(as_bytes(bytes), "piz.exr");
            REQUIRE(back.width == w);
            REQUIRE(back.height == h);
            if (type == TINYEXR_PIXELTYPE_FLOAT) {
                CHECK(wp::test::bit_identical(back, original));
            } else {
                for (std::size_t i = 0; i < back.rgb.size(); ++i) // half: 11 significant bits
                    CHECK(back.rgb[i] == Approx(original.rgb[i]).epsilon(1.0 / 1024));
            }
        }
    }
}

TEST_CASE("fuzz regressions: PFM inputs give clean errors", "[fuzz][pfm]") {
    check_image_cases("pfm", [](std::span<const unsigned char> bytes, const std::string& name) {
        return wp::decode_pfm(bytes, name);
    });
}

TEST_CASE("decode_exr and decode_pfm read a file's bytes as read_exr and read_pfm read the file",
          "[fuzz][exr][pfm]") {
    const std::filesystem::path reference =
        std::filesystem::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "hexroom-32-ref.exr";
    const wp::Image from_file = wp::read_exr(reference);
    const wp::Image from_bytes =
        wp::decode_exr(as_bytes(fuzz_regressions::read_bytes(reference)), reference.string());
    CHECK(wp::test::bit_identical(from_bytes, from_file));
    CHECK(from_bytes.metadata == from_file.metadata);

    wp::test::TempDir dir;
    const wp::Image original = wp::test::distinct_image(5, 3);
    wp::write_pfm(dir / "a.pfm", original);
    const wp::Image pfm =
        wp::decode_pfm(as_bytes(fuzz_regressions::read_bytes(dir / "a.pfm")), "a");
    CHECK(wp::test::bit_identical(pfm, wp::read_pfm(dir / "a.pfm")));
    CHECK(wp::test::bit_identical(pfm, original));

    // Errors name the file as the caller gives it.
    CHECK_THROWS_WITH(wp::decode_pfm(as_bytes("P6\n"), "x.pfm"),
                      "cannot read 'x.pfm': not a PFM file (missing 'PF' signature)");
    CHECK_THROWS_WITH(wp::decode_exr(as_bytes("not an exr"), "x.exr"),
                      "cannot read 'x.exr': not an OpenEXR file");
}
