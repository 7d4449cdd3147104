// Tokens, and locale-independent parsing of one whole token as a number,
// shared by the OBJ and ASCII PLY readers. Unlike strtod it never depends on the C locale, and
// unlike a bare std::from_chars it takes the leading '+' that some exporters
// write and reports overflow as an infinity, so that "1e999" is caught by the
// same "not finite" check as "inf" and "nan".
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string_view>
#include <system_error>

namespace wp {

// The next token of `rest` separated by spaces or tabs (empty at the end),
// which is taken off the front of `rest`.
inline std::string_view next_token(std::string_view& rest) {
    const auto begin = rest.find_first_not_of(" \t");
    if (begin == std::string_view::npos) {
        rest = {};
        return {};
    }
    rest.remove_prefix(begin);
    const auto end = std::min(rest.find_first_of(" \t"), rest.size());
    const std::string_view token = rest.substr(0, end);
    rest.remove_prefix(end);
    return token;
}

// True when all of `token` is a decimal floating-point number, "inf" or "nan".
inline bool parse_double(std::string_view token, double& out) {
    if (!token.empty() && token.front() == '+')
        token.remove_prefix(1);
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, out);
    if (ptr != end || token.empty())
        return false;
    if (ec == std::errc::result_out_of_range) {
        // from_chars leaves `out` alone on overflow or underflow; tell them apart
        // by the exponent's sign. An underflow is honestly zero.
        const bool negative = token.front() == '-';
        const auto e = token.find_first_of("eE");
        const bool tiny =
            e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
        out = tiny ? 0.0 : (negative ? -1.0 : 1.0) * std::numeric_limits<double>::infinity();
        return true;
    }
    return ec == std::errc();
}

// True when all of `token` is a decimal integer that fits in 64 bits.
inline bool parse_integer(std::string_view token, std::int64_t& out) {
    if (!token.empty() && token.front() == '+')
        token.remove_prefix(1);
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, out);
    return !token.empty() && ec == std::errc() && ptr == end;
}

} // namespace wp
