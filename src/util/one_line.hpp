// Error messages and warnings that quote input (a scene's keys, a mesh file's
// tokens, an image's channel names) must stay one line a terminal shows as it
// is: the input's control characters (newline, carriage return, escape) and
// bytes that are not well-formed UTF-8 become '?'. Used by every module's
// error type that quotes what it read (SceneError, MeshError, ImageError).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace wp {

// s with every control character (below 0x20, and 0x7f) and every byte that
// is not part of a well-formed UTF-8 sequence replaced by '?'.
std::string one_line(std::string s);

// How much of a name or token read from input a message quotes: a file may
// hold a megabyte-long `usemtl` name, which a message would echo in full.
inline constexpr std::size_t kQuotedInputBytes = 80;

// s cut to at most max_bytes plus "..." when longer, never inside a UTF-8
// sequence.
std::string excerpt(std::string_view s, std::size_t max_bytes = kQuotedInputBytes);

} // namespace wp
