// Files as whole units: read one into memory, replace one atomically, say in
// words why an operation failed, and compare extensions. Every module that
// reads or writes files (scene, image, cl, report, app) goes through here, so
// a missing file, a full disk or a failed rename reads the same everywhere.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wp {

// Thrown by the functions below. The message is one line,
// "<action> '<path>': <reason>", e.g. "cannot open 'a.exr': No such file or
// directory"; reason() is the part after the colon, for callers that name
// the file in their own words ("cannot open scene 'a.json': ...").
class FileError : public std::runtime_error {
  public:
    FileError(const std::string& action, std::string reason)
        : std::runtime_error(action + ": " + reason), reason_(std::move(reason)) {}
    const std::string& reason() const { return reason_; }

  private:
    std::string reason_;
};

// errno as text ("No such file or directory").
std::string errno_text(int err);

// The extension with its dot, in lower case (".exr" for "a/B.EXR"); "" if none.
std::string lower_extension(const std::filesystem::path& path);

// The file's contents. Throws FileError "cannot open '<path>': <reason>" (a
// directory is "Is a directory"; a FIFO, device or socket "it is a FIFO, not
// a regular file", refused without opening it, so that no read blocks or
// runs without end) or "cannot read '<path>': <reason>".
std::vector<unsigned char> read_file_bytes(const std::filesystem::path& path);
std::string read_file_text(const std::filesystem::path& path);

// Throws FileError "cannot write '<path>': directory '<dir>' does not exist"
// (or "... is not a directory") unless path's directory exists.
void check_parent_directory(const std::filesystem::path& path);

// Throws FileError "cannot write '<path>': <reason>" unless
// write_file_atomically could write path: its directory exists and takes new
// files (tried by creating and removing one), path is not a directory, and
// its name leaves room for the temporary file's suffix within the
// filesystem's name limit; an existing file at path is one its permission
// bits let this user write, or a character device or FIFO (written
// through, see below), not a block device or socket. For commands that
// check their outputs before hours of work, not after.
void check_writable(const std::filesystem::path& path);

// The path with symbolic links, "." and ".." resolved, for telling whether
// two names are the same file ("a/../b.exr" and a link to it are "b.exr"); a
// path that does not exist yet is resolved as far as it exists.
std::filesystem::path resolved_path(const std::filesystem::path& path);

// Removes the temporary file of a write_file_atomically in progress, if any.
// Async-signal-safe (it only calls unlink): for a signal handler that ends
// the process in the middle of a write, which would otherwise leave the
// temporary file behind.
void remove_pending_temp_files() noexcept;

// Whether write_file_atomically flushes the new file to disk before the
// rename. Without it, a power loss soon after can leave an empty file where
// the old one was: right for results, needless for a cache that checks its
// entries (cl/program_cache.hpp).
enum class Durability { Synced, Unsynced };

// Calls write(temp) with a fresh, empty file in the same directory as path
// (same directory, so the final rename stays on one filesystem and is
// atomic), flushes it to disk when asked and renames it over path. Readers,
// and a crash halfway through, see either the old complete file or the new
// complete one. If the writer throws or any step fails, the temporary file
// is removed, whatever was at path before is left untouched, and a FileError
// "cannot write '<path>': <reason>" is thrown.
//
// What is never replaced: an existing file whose permission bits do not let
// this user write it (even root: someone marked it read-only), a directory,
// a block device or a socket are refused with that FileError. A character
// device (/dev/null) or a FIFO is written through instead: the whole output
// is made in a temporary file in the system's temporary directory and then
// written into it; a FIFO with no reader is an error, not a wait.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& temp)>& write,
                           Durability durability = Durability::Synced);

// write_file_atomically with a writer that stores the given bytes; for
// encoders that produce the whole file in memory (EXR, PFM, PNG, JSON, CSV).
void write_bytes_atomically(const std::filesystem::path& path, const void* data, std::size_t size,
                            Durability durability = Durability::Synced);

} // namespace wp
