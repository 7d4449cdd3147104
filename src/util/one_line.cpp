#include "util/one_line.hpp"

namespace wp {

namespace {

// Length of the well-formed UTF-8 sequence at s[i], or 0 if there is none
// (a stray continuation byte, a truncated or overlong sequence, a surrogate).
std::size_t utf8_length(const std::string& s, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char b = byte(i);
    if (b < 0x80)
        return 1;
    std::size_t n = b >= 0xF0 && b <= 0xF4 ? 4 : b >= 0xE0 ? 3 : b >= 0xC2 && b < 0xE0 ? 2 : 0;
    if (n == 0 || b > 0xF4 || i + n > s.size())
        return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((byte(i + k) & 0xC0) != 0x80)
            return 0;
    const unsigned char c = byte(i + 1);
    if ((b == 0xE0 && c < 0xA0) || (b == 0xED && c >= 0xA0) || (b == 0xF0 && c < 0x90) ||
        (b == 0xF4 && c >= 0x90))
        return 0;
    return n;
}

} // namespace

std::string one_line(std::string s) {
    for (std::size_t i = 0; i < s.size();) {
        const unsigned char ch = static_cast<unsigned char>(s[i]);
        if (ch < 0x20 || ch == 0x7f) {
            s[i++] = '?';
            continue;
        }
        const std::size_t n = utf8_length(s, i);
        if (n == 0)
            s[i++] = '?'; // a terminal would garble an invalid byte, or the rest of the line
        else
            i += n;
    }
    return s;
}

std::string excerpt(std::string_view s, std::size_t max_bytes) {
    if (s.size() <= max_bytes)
        return std::string(s);
    std::size_t cut = max_bytes;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80)
        --cut; // s[cut] continues a sequence: cut before the sequence's start
    return std::string(s.substr(0, cut)) + "...";
}

} // namespace wp
