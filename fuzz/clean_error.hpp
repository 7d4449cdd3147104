// What the fuzz targets and their regression tests (tests/*/test_fuzz_regressions.cpp)
// demand of an error message or a warning: the project's rule for bad input is
// "a clear one-line error naming the problem", and a message that quotes a file's
// bytes must not carry them raw to the terminal. So a message is clean when it is
// non-empty, holds no control character (no newline, carriage return, escape)
// and is well-formed UTF-8. An exception of the reader's own error type with a
// clean message is the expected answer to a malformed input; anything else is a
// finding, like a crash.
//
// The UTF-8 check decodes each code point and tests its range (RFC 3629), a
// different method from the loader's own json::one_line (scene/json_reader.cpp),
// so that the two check each other.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace wp::fuzz {

// What is wrong with `message`, or "" when it is clean.
inline std::string message_problem(std::string_view message) {
    if (message.empty())
        return "empty message";
    std::size_t i = 0;
    while (i < message.size()) {
        const auto lead = static_cast<unsigned char>(message[i]);
        const std::string where = " at byte " + std::to_string(i);
        if (lead < 0x20 || lead == 0x7f)
            return "control character " + std::to_string(lead) + where;
        if (lead < 0x80) {
            ++i;
            continue;
        }
        // Sequence length from the lead byte, and the smallest code point that
        // needs that many bytes (anything below is an overlong encoding).
        std::size_t length = 0;
        std::uint32_t code = 0, smallest = 0;
        if ((lead & 0xE0) == 0xC0) {
            length = 2, code = lead & 0x1Fu, smallest = 0x80;
        } else if ((lead & 0xF0) == 0xE0) {
            length = 3, code = lead & 0x0Fu, smallest = 0x800;
        } else if ((lead & 0xF8) == 0xF0) {
            length = 4, code = lead & 0x07u, smallest = 0x10000;
        } else {
            return "invalid UTF-8 lead byte" + where;
        }
        if (i + length > message.size())
            return "truncated UTF-8 sequence" + where;
        for (std::size_t k = 1; k < length; ++k) {
            const auto next = static_cast<unsigned char>(message[i + k]);
            if ((next & 0xC0) != 0x80)
                return "invalid UTF-8 continuation byte" + where;
            code = (code << 6) | (next & 0x3Fu);
        }
        if (code < smallest)
            return "overlong UTF-8 sequence" + where;
        if (code >= 0xD800 && code <= 0xDFFF)
            return "UTF-8 encoded surrogate" + where;
        if (code > 0x10FFFF)
            return "code point beyond U+10FFFF" + where;
        i += length;
    }
    return "";
}

// For the fuzz targets: aborts, so that libFuzzer keeps the input, unless the
// message is clean. `what` says where the message came from.
inline void require_clean_message(std::string_view message, const char* what) {
    const std::string problem = message_problem(message);
    if (!problem.empty()) {
        std::fprintf(stderr, "%s is not a clean one-line message (%s): '%.*s'\n", what,
                     problem.c_str(), static_cast<int>(message.size()), message.data());
        std::abort();
    }
}

} // namespace wp::fuzz
