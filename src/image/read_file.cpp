#include "image/read_file.hpp"

#include "image/image.hpp"

#include <cerrno>
#include <cstdio>
#include <memory>
#include <string>
#include <system_error>

namespace wp {
namespace {

std::string errno_text(int err) {
    return std::error_code(err, std::generic_category()).message();
}

struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};

} // namespace

std::vector<unsigned char> read_file_bytes(const std::filesystem::path& path) {
    // fopen succeeds on a directory on Linux; report it as the open error it really is.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        throw ImageError("cannot open '" + path.string() + "': " + errno_text(EISDIR));
    }
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) {
        throw ImageError("cannot open '" + path.string() + "': " + errno_text(errno));
    }
    // Read in chunks rather than trusting a size from stat: the file may be a pipe or
    // change while we read, and this way the bytes returned are exactly the bytes read.
    std::vector<unsigned char> bytes;
    if (const auto hint = std::filesystem::file_size(path, ec); !ec) {
        bytes.reserve(static_cast<std::size_t>(hint));
    }
    unsigned char chunk[1 << 16];
    for (;;) {
        const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
        bytes.insert(bytes.end(), chunk, chunk + n);
        if (n < sizeof chunk) {
            break;
        }
    }
    if (std::ferror(file.get())) {
        throw ImageError("cannot read '" + path.string() + "': " + errno_text(errno));
    }
    return bytes;
}

} // namespace wp
