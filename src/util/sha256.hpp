// SHA-256 (FIPS 180-4): the hash outputs record of the scene file they were
// rendered from, the one `sha256sum` prints, so anyone can check which file
// made an image.
#pragma once

#include <cstddef>
#include <string>

namespace wp {

// The SHA-256 digest of size bytes at data, as 64 lower-case hex digits.
std::string sha256_hex(const unsigned char* data, std::size_t size);

} // namespace wp
