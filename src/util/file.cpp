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
#include <grp.h>
#include <sys/stat.h>
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

// What a non-regular file is, for messages ("a FIFO").
const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISFIFO(mode))
        return "a FIFO";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a regular file";
}

// Whether the file's permission bits let this process's user write it: by
// the owner, group or other class the user falls in, as ls shows them. Not
// access(2), which says yes to root for any file: a file someone marked
// read-only stays theirs to replace, whoever runs wavepath.
bool mode_allows_writing(const struct stat& st) {
    if (st.st_uid == ::geteuid())
        return (st.st_mode & S_IWUSR) != 0;
    bool in_group = st.st_gid == ::getegid();
    if (!in_group) {
        gid_t groups[256];
        const int count = ::getgroups(256, groups);
        for (int i = 0; i < count && !in_group; ++i)
            in_group = groups[i] == st.st_gid;
    }
    return (st.st_mode & (in_group ? S_IWGRP : S_IWOTH)) != 0;
}

// How an existing output is to be written. Regular files (and new names) are
// replaced by a rename; a character device (/dev/null) or a FIFO is written
// through, since renaming over it would replace the device node itself;
// anything else is refused. Throws FileError "<action>: <reason>".
enum class OutputKind { Replace, WriteThrough };
OutputKind output_kind(const fs::path& path, const std::string& action) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        return OutputKind::Replace; // a new file (or a dangling link, replaced as before)
    if (S_ISREG(st.st_mode)) {
        if (!mode_allows_writing(st))
            throw FileError(action, "the file is read-only (its permissions do not let this "
                                    "user write it); remove it or change its mode first");
        return OutputKind::Replace;
    }
    if (S_ISDIR(st.st_mode))
        throw FileError(action, "it is a directory");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))
        return OutputKind::WriteThrough;
    throw FileError(action, std::string("it is ") + kind_of(st.st_mode) +
                                "; outputs must be regular files, character devices or FIFOs");
}

// Writes `temp`'s bytes into the existing device or FIFO at `path`, which is
// opened, never replaced. A FIFO with no reader is an error, not a wait.
// Throws the bare reason; write_file_atomically names the path.
void copy_into(const fs::path& temp, const fs::path& path) {
    const int in = ::open(temp.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0)
        throw FileError(cannot("reopen temporary file", temp), errno_text(errno));
    const int out = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (out < 0) {
        const int err = errno;
        ::close(in);
        // The caller's message names the path: just the reason here.
        throw std::runtime_error(err == ENXIO ? "no process is reading the FIFO" : errno_text(err));
    }
    // Blocking from here on: a reader that is slow must not make the write fail.
    ::fcntl(out, F_SETFL, ::fcntl(out, F_GETFL) & ~O_NONBLOCK);
    char buffer[1 << 16];
    int err = 0;
    for (;;) {
        const ssize_t n = ::read(in, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            err = errno;
            break;
        }
        if (n == 0)
            break;
        for (ssize_t done = 0; done < n && err == 0;) {
            const ssize_t w = ::write(out, buffer + done, static_cast<std::size_t>(n - done));
            if (w < 0 && errno != EINTR)
                err = errno;
            else if (w > 0)
                done += w;
        }
        if (err != 0)
            break;
    }
    ::close(in);
    if (::close(out) != 0 && err == 0)
        err = errno;
    if (err != 0)
        throw std::runtime_error(errno_text(err));
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
    // Only regular files: a FIFO would block until a writer comes (for ever,
    // and before any signal handler can help), and a device such as
    // /dev/zero never ends. stat first, so that opening is never what blocks;
    // O_NONBLOCK and fstat after, for a file swapped in between.
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw FileError(cannot("open", path), errno_text(errno));
    if (S_ISDIR(st.st_mode))
        throw FileError(cannot("open", path), errno_text(EISDIR));
    if (!S_ISREG(st.st_mode))
        throw FileError(cannot("open", path),
                        std::string("it is ") + kind_of(st.st_mode) + ", not a regular file");
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw FileError(cannot("open", path), errno_text(errno));
    const std::unique_ptr<std::FILE, FileCloser> file(::fdopen(fd, "rb"));
    if (!file) {
        const int err = errno;
        ::close(fd);
        throw FileError(cannot("open", path), errno_text(err));
    }
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
        throw FileError(cannot("open", path), "it is not a regular file");
    // Read in chunks rather than trusting the size from stat: the file may
    // change while we read, and this way the bytes returned are exactly the
    // bytes read.
    std::vector<unsigned char> bytes;
    bytes.reserve(static_cast<std::size_t>(st.st_size));
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
    // A device or FIFO is written through, with the temporary file elsewhere.
    if (output_kind(path, cannot("write", path)) == OutputKind::WriteThrough)
        return;
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
    const OutputKind kind = output_kind(path, action);

    fs::path temp;
    std::error_code ec;
    try {
        // Written through: the whole output is made first (a failing writer
        // sends nothing), in the temporary directory, since a device's
        // directory (/dev) need not take new files.
        const fs::path dir = kind == OutputKind::WriteThrough ? fs::temp_directory_path()
                             : path.has_parent_path()         ? path.parent_path()
                                                              : fs::path(".");
        temp = create_temp_file(dir, path);
        const PendingTempGuard pending(temp);
        write(temp);
        if (kind == OutputKind::WriteThrough) {
            copy_into(temp, path);
            fs::remove(temp, ec);
            return;
        }
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
