// Whether this test program runs under the sanitizers of a -DWAVEPATH_SANITIZE
// build (docs/fuzzing.md). CMake says so with WAVEPATH_SANITIZED (the
// -fsanitize= list), since the test files themselves are compiled plain in
// that build (wavepath_plain_test_code, cmake/Sanitizers.cmake), where the
// compiler's own __SANITIZE_ADDRESS__ is not defined.
#pragma once

#include <string_view>

namespace wp::test {

#ifdef WAVEPATH_SANITIZED
inline constexpr std::string_view kSanitizers = WAVEPATH_SANITIZED;
#else
inline constexpr std::string_view kSanitizers = "";
#endif

// Whether AddressSanitizer is on. Its shadow memory reserves terabytes of
// address space, so a test that limits the address space (ulimit -v) cannot
// run under it.
inline constexpr bool kAddressSanitizer = kSanitizers.find("address") != std::string_view::npos;

} // namespace wp::test
