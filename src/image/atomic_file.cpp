#include "image/atomic_file.hpp"

#include "image/image.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace wp {
namespace {

namespace fs = std::filesystem;

std::string errno_text(int err) {
    return std::error_code(err, std::generic_category()).message();
}

// Creates a new, empty temporary file next to target and returns its path. The name
// holds the process id and a per-process counter so concurrent writers never collide;
// O_EXCL makes a stale file from a crashed run with a recycled pid a retry, not a clash.
fs::path create_temp_file(const fs::path& dir, const fs::path& target) {
    static std::atomic<unsigned long> counter{0};
    // Appended piecewise: `"." + std::string` trips a GCC 12 -Wrestrict false positive.
    std::string stem = ".";
    stem += target.filename().string();
    stem += ".tmp-";
    stem += std::to_string(getpid());
    for (int attempt = 0; attempt < 100; ++attempt) {
        const fs::path temp = dir / (stem + "-" + std::to_string(counter++));
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return temp;
        }
        if (errno != EEXIST) {
            throw ImageError("cannot create temporary file '" + temp.string() +
                             "': " + errno_text(errno));
        }
    }
    throw ImageError("cannot create a temporary file in '" + dir.string() +
                     "': too many stale temporary files");
}

// Flushes the temporary file's data to disk before the rename: without it, a power loss
// soon after the rename can leave an empty file where the old one was.
void sync_file(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        throw ImageError("cannot reopen temporary file '" + file.string() +
                         "': " + errno_text(errno));
    }
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0) {
        throw ImageError("cannot flush temporary file '" + file.string() + "': " + errno_text(err));
    }
}

} // namespace

void write_file_atomically(const fs::path& path,
                           const std::function<void(const fs::path& temp)>& write) {
    const std::string context = "cannot write '" + path.string() + "'";
    if (path.empty() || !path.has_filename()) {
        throw ImageError(context + ": not a file name");
    }
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::exists(dir, ec)) {
        throw ImageError(context + ": directory '" + dir.string() + "' does not exist");
    }
    if (!fs::is_directory(dir, ec)) {
        throw ImageError(context + ": '" + dir.string() + "' is not a directory");
    }

    fs::path temp;
    try {
        temp = create_temp_file(dir, path);
        write(temp);
        sync_file(temp);
        if (std::rename(temp.c_str(), path.c_str()) != 0) {
            throw ImageError("cannot rename '" + temp.string() + "' to '" + path.string() +
                             "': " + errno_text(errno));
        }
    } catch (const std::exception& e) {
        if (!temp.empty()) {
            fs::remove(temp, ec); // best effort: the original error is the one to report
        }
        throw ImageError(context + ": " + e.what());
    } catch (...) {
        if (!temp.empty()) {
            fs::remove(temp, ec);
        }
        throw ImageError(context + ": unknown error while writing");
    }
}

void write_bytes_atomically(const fs::path& path, const void* data, std::size_t size) {
    write_file_atomically(path, [&](const fs::path& temp) {
        std::FILE* f = std::fopen(temp.c_str(), "wb");
        if (f == nullptr) {
            throw ImageError("cannot open '" + temp.string() + "': " + errno_text(errno));
        }
        const std::size_t written = size == 0 ? 0 : std::fwrite(data, 1, size, f);
        const int write_err = errno;
        // fclose flushes, so a full disk may only show up here.
        const int close_rc = std::fclose(f);
        const int close_err = errno;
        if (written != size) {
            throw ImageError("cannot write '" + temp.string() + "': " + errno_text(write_err));
        }
        if (close_rc != 0) {
            throw ImageError("cannot write '" + temp.string() + "': " + errno_text(close_err));
        }
    });
}

} // namespace wp
