// An on-disk cache of compiled OpenCL program binaries.
//
// Entries live under $XDG_CACHE_HOME/wavepath (default ~/.cache/wavepath;
// $WAVEPATH_CACHE_DIR overrides both), one file per program, named by a
// 64-bit FNV-1a hash of everything that decides the binary: the expanded
// source text, the build options, and the device (its name and version, the
// driver version and the platform version). Each file is a 40-byte header,
// the key's text (program_cache_key_text: what the key hashes, in words),
// then the binary that clGetProgramInfo(CL_PROGRAM_BINARIES) returned:
//
//   offset  size  field
//        0     8  magic "WPCLBIN\0"
//        8     4  format version (kProgramCacheFormat), little-endian
//       12     4  key text size in bytes
//       16     8  key (the hash that also names the file)
//       24     8  payload size in bytes
//       32     8  checksum (FNV-1a 64 of the key text, then the payload)
//       40     .  key text, then payload
//
// A file that is short, has the wrong magic, version, key, key text or size,
// or whose checksum does not match is removed on load and never used; so is
// one the driver rejects (see build_program). The key text is checked as
// well as the hash because the hash alone names a file: a copied or crafted
// file of another program, under this program's name and with its hash, is
// refused by the text (options, source, device and driver) it was built from. Writes go to a
// temporary file in the same directory that is then renamed over the entry, so readers (and other
// processes writing the same entry) never see a partial file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cl/cl.hpp"

namespace wp {

// Format 1 had no key text; format 2's entries were built without the
// correctly rounded division and square root (device_workaround_options,
// program.cpp). Older entries are rejected and rebuilt.
inline constexpr std::uint32_t kProgramCacheFormat = 3;
inline constexpr std::size_t kProgramCacheHeaderSize = 40;

// FNV-1a, 64 bits. `state` continues an earlier hash.
inline constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
std::uint64_t fnv1a64(std::string_view data, std::uint64_t state = kFnvOffset);
std::uint64_t fnv1a64_bytes(const void* data, std::size_t size, std::uint64_t state = kFnvOffset);

// What identifies a device's compiler: device name, driver version and
// platform version, e.g. "pthread-skylake-avx512-AMD EPYC|3.1+debian|OpenCL 3.0 PoCL 3.1 ...".
std::string device_cache_identity(const cl::Device& device);

// The cache key of one program. Each part is hashed with its length, so no
// two different (source, options, device) triples concatenate alike.
std::uint64_t program_cache_key(std::string_view expanded_source, std::string_view options,
                                std::string_view device_identity);

// What the key hashes, as text stored in the entry and compared on load:
// "source <FNV-1a 64 of the expanded source> <bytes>\noptions <options>\n
// device <device identity>".
std::string program_cache_key_text(std::string_view expanded_source, std::string_view options,
                                   std::string_view device_identity);

// Where the program cache lives by default: $WAVEPATH_CACHE_DIR if set, else
// $XDG_CACHE_HOME/wavepath if that variable is an absolute path, else
// $HOME/.cache/wavepath; empty if none is usable.
std::filesystem::path default_program_cache_directory();

// True when the environment turns the cache off (WAVEPATH_NO_CACHE set to
// anything but "" or "0").
bool program_cache_disabled_by_environment();

// How a build uses the cache.
struct CachePolicy {
    bool enabled = false;
    std::filesystem::path directory; // empty with enabled: default_program_cache_directory()

    static CachePolicy off() { return {}; }
    // The default of build_wavefront_program: on, in the default directory,
    // unless WAVEPATH_NO_CACHE says otherwise.
    static CachePolicy from_environment();
    static CachePolicy in(std::filesystem::path dir) { return {true, std::move(dir)}; }
};

// The result of looking an entry up.
struct CacheLookup {
    std::optional<std::vector<unsigned char>> binary; // set on a valid entry
    std::string rejected;                             // why an entry was removed, if one was
};

// One cache directory. Loading and storing never throw for I/O problems: a
// cache that cannot be read or written behaves as an empty one (store()
// returns the reason instead).
class ProgramCache {
  public:
    explicit ProgramCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

    const std::filesystem::path& directory() const { return directory_; }
    std::filesystem::path entry_path(std::uint64_t key) const;

    // The entry's binary, if it is present, intact and built from key_text;
    // a damaged, stale or foreign entry is removed and its fault returned in
    // `rejected`.
    CacheLookup load(std::uint64_t key, std::string_view key_text) const;
    // Stores atomically, creating the directory if needed. Returns "" on
    // success, else why not (the build goes on without the cache).
    std::string store(std::uint64_t key, std::string_view key_text,
                      const std::vector<unsigned char>& binary) const;
    void remove(std::uint64_t key) const;

    // An entry file's bytes: header, key text and payload.
    static std::vector<unsigned char> encode(std::uint64_t key, std::string_view key_text,
                                             const std::vector<unsigned char>& binary);
    // The payload of an entry's bytes, or the reason it is unusable.
    static std::optional<std::vector<unsigned char>> decode(std::uint64_t key,
                                                            std::string_view key_text,
                                                            const std::vector<unsigned char>& bytes,
                                                            std::string& fault);

  private:
    std::filesystem::path directory_;
};

} // namespace wp
