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

// Under AddressSanitizer (the CI's sanitizer build) the leak this input found in
// tinyexr's failure path fails the test when the process exits.
TEST_CASE("fuzz regressions: EXR inputs give clean errors", "[fuzz][exr]") {
    check_image_cases("exr", [](std::span<const unsigned char> bytes, const std::string& name) {
        return wp::decode_exr(bytes, name);
    });
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
