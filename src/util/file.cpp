#include "util/file.hpp"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace wp {
namespace {

namespace fs = std::filesystem;

// The temporary files of writes in progress, for remove_pending_temp_files
// in a signal handler: fixed buffers (no allocation there) published through
// an atomic flag, so the handler sees either no path or a complete one.
struct PendingTemp {
    std::atomic<bool> set{false};
    char path[PATH_MAX];
};
PendingTemp g_pending[4];

// Registers `temp` in a free slot for as long as the object lives; a path
// too long or no free slot (nested writes) just goes unregistered.
class PendingTempGuard {
  public:
    explicit PendingTempGuard(const fs::path& temp) {
        const std::string& text = temp.native();
        if (text.size() >= PATH_MAX)
            return;
        for (PendingTemp& slot : g_pending) {
            if (slot.set.load())
                continue;
            std::memcpy(slot.path, text.c_str(), text.size() + 1);
            slot.set.store(true);
            slot_ = &slot;
            return;
        }
    }
    ~PendingTempGuard() {
        if (slot_ != nullptr)
            slot_->set.store(false);
    }
    PendingTempGuard(const PendingTempGuard&) = delete;
    PendingTempGuard& operator=(const PendingTempGuard&) = delete;

  private:
    PendingTemp* slot_ = nullptr;
};

// The most a temporary file's name adds to the target's: ".", ".tmp-", a pid
// and "-" and a counter (create_temp_file).
constexpr std::size_t kTempSuffixBytes = 1 + 5 + 10 + 1 + 20;

struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};

// "cannot <verb> '<path>'", the action part of every message here.
std::string cannot(const char* verb, const fs::path& path) {
    return std::string("cannot ") + verb + " '" + path.string() + "'";
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
        if (errno != EEXIST)
            throw FileError(cannot("create temporary file", temp), errno_text(errno));
    }
    throw FileError(std::string("cannot create a temporary file in '") + dir.string() + "'",
                    "too many stale temporary files");
}

// Flushes the temporary file's data to disk before the rename.
void sync_file(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        throw FileError(cannot("reopen temporary file", file), errno_text(errno));
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0)
        throw FileError(cannot("flush temporary file", file), errno_text(err));
}

} // namespace

std::string errno_text(int err) {
    return std::error_code(err, std::generic_category()).message();
}

std::string lower_extension(const fs::path& path) {
    std::string extension = path.extension().string();
    for (char& c : extension)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

std::vector<unsigned char> read_file_bytes(const fs::path& path) {
    // fopen succeeds on a directory on Linux; report it as the open error it really is.
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw FileError(cannot("open", path), errno_text(EISDIR));
    const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw FileError(cannot("open", path), errno_text(errno));
    // Read in chunks rather than trusting a size from stat: the file may be a pipe or
    // change while we read, and this way the bytes returned are exactly the bytes read.
    std::vector<unsigned char> bytes;
    if (const auto hint = fs::file_size(path, ec); !ec)
        bytes.reserve(static_cast<std::size_t>(hint));
    unsigned char chunk[1 << 16];
    for (;;) {
        const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
        bytes.insert(bytes.end(), chunk, chunk + n);
        if (n < sizeof chunk)
            break;
    }
    if (std::ferror(file.get()))
        throw FileError(cannot("read", path), errno_text(errno));
    return bytes;
}

std::string read_file_text(const fs::path& path) {
    const std::vector<unsigned char> bytes = read_file_bytes(path);
    return std::string(bytes.begin(), bytes.end());
}

void check_parent_directory(const fs::path& path) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::exists(dir, ec))
        throw FileError(cannot("write", path), "directory '" + dir.string() + "' does not exist");
    if (!fs::is_directory(dir, ec))
        throw FileError(cannot("write", path), "'" + dir.string() + "' is not a directory");
}

void check_writable(const fs::path& path) {
    check_parent_directory(path);
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw FileError(cannot("write", path), "it is a directory");
    const long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    const std::size_t limit = name_max > 0 ? static_cast<std::size_t>(name_max) : NAME_MAX;
    const std::size_t name = path.filename().native().size();
    if (name + kTempSuffixBytes > limit)
        throw FileError(
            cannot("write", path),
            "file name too long (" + std::to_string(name) + " bytes; at most " +
                std::to_string(limit > kTempSuffixBytes ? limit - kTempSuffixBytes : 0) +
                " here, leaving room for the temporary file's suffix)");
    // The temporary file is created in dir, so dir must take new entries (a
    // writable file at path is not enough). Creating one is the only test
    // that also holds for root and read-only mounts, where access() says yes.
    try {
        const fs::path probe = create_temp_file(dir, path);
        ::unlink(probe.c_str());
    } catch (const FileError& e) {
        throw FileError(cannot("write", path), "cannot create files in directory '" + dir.string() +
                                                   "' (" + e.reason() + ")");
    }
}

fs::path resolved_path(const fs::path& path) {
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    if (ec)
        return path.lexically_normal();
    fs::path resolved = fs::weakly_canonical(absolute, ec);
    return ec ? absolute.lexically_normal() : resolved;
}

void remove_pending_temp_files() noexcept {
    for (PendingTemp& slot : g_pending)
        if (slot.set.load())
            ::unlink(slot.path);
}

void write_file_atomically(const fs::path& path,
                           const std::function<void(const fs::path& temp)>& write,
                           Durability durability) {
    const std::string action = cannot("write", path);
    if (path.empty() || !path.has_filename())
        throw FileError(action, "not a file name");
    check_parent_directory(path);

    fs::path temp;
    std::error_code ec;
    try {
        temp = create_temp_file(path.has_parent_path() ? path.parent_path() : fs::path("."), path);
        const PendingTempGuard pending(temp);
        write(temp);
        if (durability == Durability::Synced)
            sync_file(temp);
        if (std::rename(temp.c_str(), path.c_str()) != 0)
            throw FileError("cannot rename '" + temp.string() + "' to '" + path.string() + "'",
                            errno_text(errno));
    } catch (const std::exception& e) {
        if (!temp.empty())
            fs::remove(temp, ec); // best effort: the original error is the one to report
        throw FileError(action, e.what());
    } catch (...) {
        if (!temp.empty())
            fs::remove(temp, ec);
        throw FileError(action, "unknown error while writing");
    }
}

void write_bytes_atomically(const fs::path& path, const void* data, std::size_t size,
                            Durability durability) {
    write_file_atomically(
        path,
        [&](const fs::path& temp) {
            std::FILE* file = std::fopen(temp.c_str(), "wb");
            if (file == nullptr)
                throw FileError(cannot("open", temp), errno_text(errno));
            const std::size_t written = size == 0 ? 0 : std::fwrite(data, 1, size, file);
            const int write_err = errno;
            // fclose flushes, so a full disk may only show up here.
            const int close_rc = std::fclose(file);
            const int close_err = errno;
            if (written != size)
                throw FileError(cannot("write", temp), errno_text(write_err));
            if (close_rc != 0)
                throw FileError(cannot("write", temp), errno_text(close_err));
        },
        durability);
}

} // namespace wp
