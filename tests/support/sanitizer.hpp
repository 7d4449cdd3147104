// The sanitizer build (-DWAVEPATH_SANITIZE, docs/fuzzing.md) runs host code
// several times slower (the 10^5-material load: 0.3 s in Release, 3.1 s under
// ASan + UBSan at -O1). Time limits that are there to catch a quadratic
// algorithm are multiplied by kTimeLimitScale, which keeps them far below
// what the quadratic version takes (minutes).
#pragma once

namespace wp::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
inline constexpr double kTimeLimitScale = 10.0; // gcc
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
inline constexpr double kTimeLimitScale = 10.0; // clang
#else
inline constexpr double kTimeLimitScale = 1.0;
#endif
#else
inline constexpr double kTimeLimitScale = 1.0;
#endif

// Whether AddressSanitizer is on. Its shadow memory reserves terabytes of
// address space, so a test that limits the address space (ulimit -v) cannot
// run under it.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

} // namespace wp::test
