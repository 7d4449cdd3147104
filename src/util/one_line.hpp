// Error messages and warnings that quote input (a scene's keys, a mesh file's
// tokens, an image's channel names) must stay one line a terminal shows as it
// is: the input's control characters (newline, carriage return, escape) and
// bytes that are not well-formed UTF-8 become '?'. Used by every module's
// error type that quotes what it read (SceneError, MeshError, ImageError).
#pragma once

#include <string>

namespace wp {

// s with every control character (below 0x20, and 0x7f) and every byte that
// is not part of a well-formed UTF-8 sequence replaced by '?'.
std::string one_line(std::string s);

} // namespace wp
