// printf-style formatting into a std::string, for the few places that need
// fixed digits (tables, metadata, messages).
#pragma once

#include <cstdio>
#include <string>

namespace wp {

// The text of std::snprintf(pattern, values...), up to 511 characters.
template <typename... Values> std::string format_text(const char* pattern, Values... values) {
    char text[512];
    std::snprintf(text, sizeof text, pattern, values...);
    return text;
}

} // namespace wp
