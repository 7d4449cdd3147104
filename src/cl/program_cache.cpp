#include "cl/program_cache.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "util/file.hpp"

namespace wp {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'W', 'P', 'C', 'L', 'B', 'I', 'N', '\0'};
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

void put32(std::vector<unsigned char>& out, std::size_t at, std::uint32_t value) {
    for (int i = 0; i < 4; ++i)
        out[at + static_cast<std::size_t>(i)] = static_cast<unsigned char>(value >> (8 * i));
}

void put64(std::vector<unsigned char>& out, std::size_t at, std::uint64_t value) {
    for (int i = 0; i < 8; ++i)
        out[at + static_cast<std::size_t>(i)] = static_cast<unsigned char>(value >> (8 * i));
}

std::uint32_t get32(const std::vector<unsigned char>& in, std::size_t at) {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i)
        value |= static_cast<std::uint32_t>(in[at + static_cast<std::size_t>(i)]) << (8 * i);
    return value;
}

std::uint64_t get64(const std::vector<unsigned char>& in, std::size_t at) {
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i)
        value |= static_cast<std::uint64_t>(in[at + static_cast<std::size_t>(i)]) << (8 * i);
    return value;
}

std::uint64_t hash_part(std::string_view part, std::uint64_t state) {
    std::uint64_t size = part.size();
    unsigned char size_bytes[8];
    for (int i = 0; i < 8; ++i)
        size_bytes[i] = static_cast<unsigned char>(size >> (8 * i));
    return fnv1a64(part, fnv1a64_bytes(size_bytes, sizeof size_bytes, state));
}

std::string hex(std::uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

// What the first line in which an entry's key text differs from the
// expected one is about: "another source", "other options" or "another
// device or driver".
std::string first_difference(std::string_view stored, std::string_view expected) {
    for (;;) {
        const std::size_t stored_end = stored.find('\n');
        const std::size_t expected_end = expected.find('\n');
        const std::string_view line = expected.substr(0, expected_end);
        if (stored.substr(0, stored_end) != line || stored_end == std::string_view::npos ||
            expected_end == std::string_view::npos) {
            const std::string_view field = line.substr(0, line.find(' '));
            return field == "options"  ? "other options"
                   : field == "device" ? "another device or driver"
                                       : "another source";
        }
        stored.remove_prefix(stored_end + 1);
        expected.remove_prefix(expected_end + 1);
    }
}

} // namespace

std::uint64_t fnv1a64_bytes(const void* data, std::size_t size, std::uint64_t state) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        state ^= bytes[i];
        state *= kFnvPrime;
    }
    return state;
}

std::uint64_t fnv1a64(std::string_view data, std::uint64_t state) {
    return fnv1a64_bytes(data.data(), data.size(), state);
}

std::string device_cache_identity(const cl::Device& device) {
    cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>(), true);
    return device.getInfo<CL_DEVICE_NAME>().c_str() + std::string("|") +
           device.getInfo<CL_DEVICE_VERSION>().c_str() + "|" +
           device.getInfo<CL_DRIVER_VERSION>().c_str() + "|" +
           platform.getInfo<CL_PLATFORM_VERSION>().c_str();
}

std::uint64_t program_cache_key(std::string_view expanded_source, std::string_view options,
                                std::string_view device_identity) {
    std::uint64_t state = hash_part("wavepath program cache", kFnvOffset);
    state = hash_part(std::to_string(kProgramCacheFormat), state);
    state = hash_part(expanded_source, state);
    state = hash_part(options, state);
    return hash_part(device_identity, state);
}

std::string program_cache_key_text(std::string_view expanded_source, std::string_view options,
                                   std::string_view device_identity) {
    std::string text = "source " + hex(fnv1a64(expanded_source)) + " " +
                       std::to_string(expanded_source.size()) + "\noptions ";
    text.append(options).append("\ndevice ").append(device_identity);
    return text;
}

fs::path default_program_cache_directory() {
    const char* own = std::getenv("WAVEPATH_CACHE_DIR");
    if (own != nullptr && own[0] != '\0')
        return fs::path(own);
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    if (xdg != nullptr && xdg[0] == '/') // the XDG spec: relative paths are ignored
        return fs::path(xdg) / "wavepath";
    const char* home = std::getenv("HOME");
    if (home != nullptr && home[0] != '\0')
        return fs::path(home) / ".cache" / "wavepath";
    return {};
}

bool program_cache_disabled_by_environment() {
    const char* value = std::getenv("WAVEPATH_NO_CACHE");
    return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

CachePolicy CachePolicy::from_environment() {
    if (program_cache_disabled_by_environment())
        return off();
    return {true, default_program_cache_directory()};
}

fs::path ProgramCache::entry_path(std::uint64_t key) const {
    return directory_ / (hex(key) + ".clbin");
}

std::vector<unsigned char> ProgramCache::encode(std::uint64_t key, std::string_view key_text,
                                                const std::vector<unsigned char>& binary) {
    std::vector<unsigned char> bytes(kProgramCacheHeaderSize + key_text.size() + binary.size());
    std::memcpy(bytes.data(), kMagic, sizeof kMagic);
    put32(bytes, 8, kProgramCacheFormat);
    put32(bytes, 12, static_cast<std::uint32_t>(key_text.size()));
    put64(bytes, 16, key);
    put64(bytes, 24, binary.size());
    put64(bytes, 32, fnv1a64_bytes(binary.data(), binary.size(), fnv1a64(key_text)));
    if (!key_text.empty())
        std::memcpy(bytes.data() + kProgramCacheHeaderSize, key_text.data(), key_text.size());
    if (!binary.empty())
        std::memcpy(bytes.data() + kProgramCacheHeaderSize + key_text.size(), binary.data(),
                    binary.size());
    return bytes;
}

std::optional<std::vector<unsigned char>>
ProgramCache::decode(std::uint64_t key, std::string_view key_text,
                     const std::vector<unsigned char>& bytes, std::string& fault) {
    if (bytes.size() < kProgramCacheHeaderSize) {
        fault = "truncated header (" + std::to_string(bytes.size()) + " bytes)";
        return std::nullopt;
    }
    if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
        fault = "bad magic";
        return std::nullopt;
    }
    if (get32(bytes, 8) != kProgramCacheFormat) {
        fault = "format version " + std::to_string(get32(bytes, 8)) + ", expected " +
                std::to_string(kProgramCacheFormat);
        return std::nullopt;
    }
    if (get64(bytes, 16) != key) {
        fault = "key mismatch";
        return std::nullopt;
    }
    const std::uint64_t text_size = get32(bytes, 12);
    const std::uint64_t size = get64(bytes, 24);
    const std::uint64_t held = bytes.size() - kProgramCacheHeaderSize;
    if (text_size > held || size != held - text_size) {
        fault = "size mismatch (header says " + std::to_string(text_size) + " + " +
                std::to_string(size) + " bytes, file holds " + std::to_string(held) + ")";
        return std::nullopt;
    }
    if (size == 0) {
        fault = "empty binary";
        return std::nullopt;
    }
    const unsigned char* text = bytes.data() + kProgramCacheHeaderSize;
    const unsigned char* payload = text + text_size;
    if (fnv1a64_bytes(payload, static_cast<std::size_t>(size),
                      fnv1a64_bytes(text, static_cast<std::size_t>(text_size))) !=
        get64(bytes, 32)) {
        fault = "checksum mismatch";
        return std::nullopt;
    }
    const std::string_view stored(reinterpret_cast<const char*>(text),
                                  static_cast<std::size_t>(text_size));
    if (stored != key_text) {
        fault = "its stored key is for " + first_difference(stored, key_text);
        return std::nullopt;
    }
    return std::vector<unsigned char>(payload, payload + size);
}

CacheLookup ProgramCache::load(std::uint64_t key, std::string_view key_text) const {
    CacheLookup result;
    if (directory_.empty())
        return result;
    const fs::path path = entry_path(key);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        return result; // a plain miss
    try {
        result.binary = decode(key, key_text, read_file_bytes(path), result.rejected);
        if (result.binary)
            return result;
    } catch (const FileError& e) {
        result.rejected = "read error: " + e.reason();
    }
    remove(key);
    return result;
}

std::string ProgramCache::store(std::uint64_t key, std::string_view key_text,
                                const std::vector<unsigned char>& binary) const {
    if (directory_.empty())
        return "no cache directory (neither XDG_CACHE_HOME nor HOME is set)";
    std::error_code ec;
    fs::create_directories(directory_, ec);
    if (ec)
        return "cannot create '" + directory_.string() + "': " + ec.message();
    // Unsynced: after a crash an entry may be empty or partial, which load()
    // detects (size and checksum) and replaces.
    const std::vector<unsigned char> bytes = encode(key, key_text, binary);
    try {
        write_bytes_atomically(entry_path(key), bytes.data(), bytes.size(), Durability::Unsynced);
    } catch (const FileError& e) {
        return e.what();
    }
    return "";
}

void ProgramCache::remove(std::uint64_t key) const {
    std::error_code ec;
    fs::remove(entry_path(key), ec); // best effort: another process may have removed it
}

} // namespace wp
