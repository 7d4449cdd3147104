// libFuzzer target: bytes as an image file, through decode_exr (image/exr.hpp;
// tinyexr underneath) or decode_pfm (image/pfm.hpp), the in-memory forms of the
// readers behind read_image. Built twice, as exr_fuzzer and pfm_fuzzer;
// WAVEPATH_FUZZ_IMAGE_DECODER names the function.
//
// An ImageError with a clean one-line message (clean_error.hpp) is the
// expected answer to bad input; anything else is a finding, and so is a decoded
// image whose pixel buffer does not match its size (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "clean_error.hpp"
#include "image/exr.hpp"
#include "image/pfm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const wp::Image image = wp::WAVEPATH_FUZZ_IMAGE_DECODER(
            std::span<const unsigned char>(data, size), "fuzz-input");
        if (!image.has_valid_shape() || image.width == 0 || image.height == 0) {
            std::fprintf(stderr, "decoded a %dx%d image holding %zu floats\n", image.width,
                         image.height, image.rgb.size());
            std::abort();
        }
    } catch (const wp::ImageError& error) {
        wp::fuzz::require_clean_message(error.what(), "an ImageError");
    }
    return 0;
}
