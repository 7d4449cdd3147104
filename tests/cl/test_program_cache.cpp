// The on-disk program binary cache: keys, entry format, damage detection,
// and builds through it. Every test here uses its own temporary cache
// directory, never the user's.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "cl/program.hpp"
#include "cl/program_cache.hpp"
#include "support/env_guard.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

using namespace wp;

namespace {

using test::EnvGuard;

// A kernel small enough to build in a moment; `tag` changes the source text.
std::string add_kernel(const std::string& tag = "") {
    return "/* " + tag +
           " */\n#include \"wp_shared.h\"\n"
           "__kernel void add(__global wp_uint* data, wp_uint amount) {\n"
           "    data[get_global_id(0)] += amount + ADD_EXTRA;\n"
           "}\n";
}

const std::string kOptions = "-D ADD_EXTRA=1";

BuiltProgram build_add(const std::filesystem::path& dir, const std::string& source = add_kernel(),
                       const std::string& options = kOptions) {
    DeviceContext& device = test::device();
    return build_program(device.context, device.info.device, source, "add.cl", options,
                         CachePolicy::in(dir));
}

// Runs the add kernel of `program` on {1, 2, 3, 4} with amount 10.
std::vector<cl_uint> run_add(const cl::Program& program) {
    DeviceContext& device = test::device();
    std::vector<cl_uint> data{1, 2, 3, 4};
    cl::Buffer buffer(device.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      sizeof(cl_uint) * data.size(), data.data());
    cl::Kernel kernel(program, "add");
    kernel.setArg(0, buffer);
    kernel.setArg(1, cl_uint{10});
    device.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(data.size()),
                                      cl::NullRange);
    device.queue.enqueueReadBuffer(buffer, CL_TRUE, 0, sizeof(cl_uint) * data.size(), data.data());
    return data;
}

const std::vector<cl_uint> kAdded{12, 13, 14, 15};

// Bytes before an entry's payload: the header and the key text.
std::size_t entry_header_size(const std::vector<unsigned char>& entry) {
    REQUIRE(entry.size() >= kProgramCacheHeaderSize);
    std::size_t text = 0;
    for (int i = 0; i < 4; ++i)
        text |= static_cast<std::size_t>(entry[12 + static_cast<std::size_t>(i)]) << (8 * i);
    return kProgramCacheHeaderSize + text;
}

std::vector<std::string> entry_files(const test::TempDir& dir) {
    std::vector<std::string> names = dir.entries();
    std::sort(names.begin(), names.end());
    return names;
}

} // namespace

TEST_CASE("program cache: FNV-1a 64 matches the reference test vectors") {
    CHECK(fnv1a64("") == 0xcbf29ce484222325ull);
    CHECK(fnv1a64("a") == 0xaf63dc4c8601ec8cull);
    CHECK(fnv1a64("foobar") == 0x85944171f73967e8ull);
    // Continuing a hash equals hashing the concatenation.
    CHECK(fnv1a64("bar", fnv1a64("foo")) == fnv1a64("foobar"));
}

TEST_CASE("program cache: the key depends on source, options and device, part by part") {
    const std::uint64_t key = program_cache_key("source", "-D A=1", "device|1.0|3.0");
    CHECK(key == program_cache_key("source", "-D A=1", "device|1.0|3.0"));
    CHECK(key != program_cache_key("source ", "-D A=1", "device|1.0|3.0"));
    CHECK(key != program_cache_key("source", "-D A=2", "device|1.0|3.0"));
    CHECK(key != program_cache_key("source", "-D A=1", "device|1.1|3.0"));
    // Parts are length-prefixed: moving text across a boundary changes the key.
    CHECK(program_cache_key("ab", "c", "d") != program_cache_key("a", "bc", "d"));
    CHECK(program_cache_key("a", "bc", "d") != program_cache_key("a", "b", "cd"));
}

TEST_CASE("program cache: the device identity names the device, its driver and its platform") {
    DeviceContext& device = test::device();
    std::string identity = device_cache_identity(device.info.device);
    CHECK(identity.find(device.info.name) != std::string::npos);
    CHECK(identity.find(device.info.driver_version) != std::string::npos);
    CHECK(identity == device_cache_identity(device.info.device));
}

TEST_CASE("program cache: the directory: WAVEPATH_CACHE_DIR, XDG_CACHE_HOME, HOME") {
    {
        EnvGuard own("WAVEPATH_CACHE_DIR", "/tmp/own");
        EnvGuard xdg("XDG_CACHE_HOME", "/somewhere/cache");
        CHECK(default_program_cache_directory() == std::filesystem::path("/tmp/own"));
    }
    EnvGuard own("WAVEPATH_CACHE_DIR", nullptr);
    {
        EnvGuard xdg("XDG_CACHE_HOME", "/somewhere/cache");
        CHECK(default_program_cache_directory() ==
              std::filesystem::path("/somewhere/cache/wavepath"));
    }
    {
        EnvGuard xdg("XDG_CACHE_HOME", "relative/cache"); // ignored, as the XDG spec says
        EnvGuard home("HOME", "/home/someone");
        CHECK(default_program_cache_directory() ==
              std::filesystem::path("/home/someone/.cache/wavepath"));
    }
    {
        EnvGuard xdg("XDG_CACHE_HOME", nullptr);
        EnvGuard home("HOME", nullptr);
        CHECK(default_program_cache_directory().empty());
    }
}

TEST_CASE("program cache: WAVEPATH_NO_CACHE turns the default cache off") {
    {
        EnvGuard off("WAVEPATH_NO_CACHE", nullptr);
        CHECK_FALSE(program_cache_disabled_by_environment());
        CHECK(CachePolicy::from_environment().enabled);
    }
    for (const char* value : {"1", "yes"}) {
        EnvGuard off("WAVEPATH_NO_CACHE", value);
        CHECK(program_cache_disabled_by_environment());
        CHECK_FALSE(CachePolicy::from_environment().enabled);
    }
    for (const char* value : {"", "0"}) {
        EnvGuard off("WAVEPATH_NO_CACHE", value);
        CHECK_FALSE(program_cache_disabled_by_environment());
    }
}

TEST_CASE("program cache: entries round-trip and every kind of damage is rejected") {
    const std::uint64_t key = 0x0123456789abcdefull;
    const std::string text = program_cache_key_text("source", "-D A=1", "device|1.0|3.0");
    const std::vector<unsigned char> binary{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    const std::vector<unsigned char> entry = ProgramCache::encode(key, text, binary);
    REQUIRE(entry.size() == kProgramCacheHeaderSize + text.size() + binary.size());

    std::string fault;
    auto decoded = ProgramCache::decode(key, text, entry, fault);
    REQUIRE(decoded);
    CHECK(*decoded == binary);
    CHECK(fault.empty());

    auto rejected = [&](std::vector<unsigned char> bytes, std::uint64_t with_key = 0) {
        std::string why;
        bool ok = ProgramCache::decode(with_key ? with_key : key, text, bytes, why).has_value();
        CHECK_FALSE(why.empty());
        return !ok ? why : std::string("accepted");
    };
    CHECK(rejected({}).find("truncated header") != std::string::npos);
    CHECK(rejected({entry.begin(), entry.begin() + 39}).find("truncated header") !=
          std::string::npos);
    CHECK(rejected({entry.begin(), entry.end() - 1}).find("size mismatch") != std::string::npos);
    std::vector<unsigned char> longer = entry;
    longer.push_back(0);
    CHECK(rejected(longer).find("size mismatch") != std::string::npos);
    std::vector<unsigned char> bad_magic = entry;
    bad_magic[0] = 'X';
    CHECK(rejected(bad_magic) == "bad magic");
    std::vector<unsigned char> old_format = entry;
    old_format[8] = static_cast<unsigned char>(kProgramCacheFormat + 1);
    CHECK(rejected(old_format).find("format version") != std::string::npos);
    CHECK(rejected(entry, key + 1) == "key mismatch");
    std::vector<unsigned char> flipped = entry;
    flipped.back() ^= 0x40;
    CHECK(rejected(flipped) == "checksum mismatch");
    CHECK(rejected(ProgramCache::encode(key, text, {})) == "empty binary");
    std::vector<unsigned char> text_size = entry;
    text_size[12] ^= 0x01;
    CHECK(rejected(text_size).find("size mismatch") != std::string::npos);
}

TEST_CASE("program cache: the key's text is stored in the entry and must match") {
    // The hash names the file and is in the header, so a copied or crafted
    // entry of another program can carry it: the text it hashes (source
    // hash, options, device and driver) must match as well.
    const std::string source = "__kernel void k() {}";
    const std::string text = program_cache_key_text(source, "-D A=1", "cpu|OpenCL 3.0|5.0|PoCL");
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a64(source)));
    CHECK(text ==
          "source " + std::string(hash) + " 20\noptions -D A=1\ndevice cpu|OpenCL 3.0|5.0|PoCL");
    const std::uint64_t key = 42;
    const std::vector<unsigned char> binary{9, 8, 7};
    struct Foreign {
        std::string text;
        std::string fault;
    };
    for (const Foreign& f : {
             Foreign{program_cache_key_text(source + " ", "-D A=1", "cpu|OpenCL 3.0|5.0|PoCL"),
                     "its stored key is for another source"},
             Foreign{program_cache_key_text(source, "-D A=2", "cpu|OpenCL 3.0|5.0|PoCL"),
                     "its stored key is for other options"},
             Foreign{program_cache_key_text(source, "-D A=1", "cpu|OpenCL 3.0|5.1|PoCL"),
                     "its stored key is for another device or driver"},
             Foreign{"", "its stored key is for another source"},
         }) {
        INFO(f.text);
        std::string fault;
        CHECK_FALSE(
            ProgramCache::decode(key, text, ProgramCache::encode(key, f.text, binary), fault));
        CHECK(fault == f.fault);
    }
    // A format-1 entry (no key text) is stale: rejected, then rebuilt.
    std::vector<unsigned char> old = ProgramCache::encode(key, text, binary);
    old[8] = 1;
    std::string fault;
    CHECK_FALSE(ProgramCache::decode(key, text, old, fault));
    CHECK(fault == "format version 1, expected " + std::to_string(kProgramCacheFormat));
}

TEST_CASE("program cache: a second build is a hit, and the cached program runs") {
    test::TempDir dir;
    BuiltProgram first = build_add(dir.path());
    CHECK(first.cache == CacheOutcome::Miss);
    CHECK_FALSE(first.cache_hit);
    CHECK(first.cache_note.empty());
    CHECK(std::filesystem::exists(first.cache_file));
    CHECK(run_add(first.program) == kAdded);

    BuiltProgram second = build_add(dir.path());
    CHECK(second.cache == CacheOutcome::Hit);
    CHECK(second.cache_hit);
    CHECK(second.cache_file == first.cache_file);
    CHECK(second.options == kOptions);
    CHECK(run_add(second.program) == kAdded);

    // One entry file and no temporary files left behind.
    CHECK(entry_files(dir).size() == 1);
    CHECK(std::filesystem::path(first.cache_file).extension() == ".clbin");
}

TEST_CASE("program cache: the entry's name is the key of expanded source, options and device") {
    test::TempDir dir;
    DeviceContext& device = test::device();
    BuiltProgram built = build_add(dir.path());
    std::uint64_t key = program_cache_key(expand_includes(add_kernel(), "add.cl"), kOptions,
                                          device_cache_identity(device.info.device));
    CHECK(built.cache_file == ProgramCache(dir.path()).entry_path(key).string());
}

TEST_CASE("program cache: changing the source, an option or the device misses") {
    test::TempDir dir;
    REQUIRE(build_add(dir.path()).cache == CacheOutcome::Miss);
    REQUIRE(build_add(dir.path()).cache == CacheOutcome::Hit);

    // Source: even a comment changes the text, hence the key.
    CHECK(build_add(dir.path(), add_kernel("changed")).cache == CacheOutcome::Miss);
    // An option.
    CHECK(build_add(dir.path(), add_kernel(), "-D ADD_EXTRA=1 -D UNUSED=2").cache ==
          CacheOutcome::Miss);
    // An included header: the key covers the expanded text, so editing an
    // embedded header (here: a different one included) misses too.
    std::string other_header = add_kernel();
    other_header.replace(other_header.find("wp_shared.h"), 11, "rng.h");
    CHECK(build_add(dir.path(), other_header).cache == CacheOutcome::Miss);

    // The device: a valid entry stored under another device's identity is not
    // found for this one. (The binary stored is this device's, so the test
    // can only fail by finding it.)
    test::TempDir other;
    DeviceContext& device = test::device();
    const std::string expanded = expand_includes(add_kernel("device"), "add.cl");
    BuiltProgram donor = build_add(other.path(), add_kernel("device"));
    std::vector<unsigned char> binary = test::read_bytes(donor.cache_file);
    binary.erase(binary.begin(),
                 binary.begin() + static_cast<std::ptrdiff_t>(entry_header_size(binary)));
    ProgramCache cache(dir.path());
    const std::uint64_t foreign_key =
        program_cache_key(expanded, kOptions, device_cache_identity(device.info.device) + "|other");
    REQUIRE(cache
                .store(foreign_key,
                       program_cache_key_text(expanded, kOptions,
                                              device_cache_identity(device.info.device) + "|other"),
                       binary)
                .empty());
    CHECK(build_add(dir.path(), add_kernel("device")).cache == CacheOutcome::Miss);
    CHECK(std::filesystem::exists(cache.entry_path(foreign_key))); // untouched
}

TEST_CASE("program cache: a truncated entry is detected, removed and rebuilt") {
    test::TempDir dir;
    BuiltProgram first = build_add(dir.path());
    REQUIRE(first.cache == CacheOutcome::Miss);
    std::vector<unsigned char> bytes = test::read_bytes(first.cache_file);
    REQUIRE(bytes.size() > kProgramCacheHeaderSize + 16);

    for (std::size_t keep :
         {bytes.size() / 2, kProgramCacheHeaderSize, std::size_t{7}, std::size_t{0}}) {
        INFO("truncated to " << keep << " bytes");
        test::write_bytes(first.cache_file, {bytes.begin(), bytes.begin() + keep});
        BuiltProgram rebuilt = build_add(dir.path());
        CHECK(rebuilt.cache == CacheOutcome::Rejected);
        CHECK_FALSE(rebuilt.cache_hit);
        CHECK_FALSE(rebuilt.cache_note.empty());
        CHECK(run_add(rebuilt.program) == kAdded);
        // The rebuilt program replaced the damaged entry: the next build hits.
        CHECK(test::read_bytes(first.cache_file).size() == bytes.size());
        CHECK(build_add(dir.path()).cache == CacheOutcome::Hit);
    }
}

TEST_CASE("program cache: a corrupt payload or a binary the driver refuses is rebuilt") {
    test::TempDir dir;
    BuiltProgram first = build_add(dir.path());
    std::vector<unsigned char> bytes = test::read_bytes(first.cache_file);

    SECTION("a flipped byte fails the checksum") {
        bytes[bytes.size() / 2] ^= 0x01;
        test::write_bytes(first.cache_file, bytes);
        BuiltProgram rebuilt = build_add(dir.path());
        CHECK(rebuilt.cache == CacheOutcome::Rejected);
        CHECK(rebuilt.cache_note == "checksum mismatch");
        CHECK(run_add(rebuilt.program) == kAdded);
    }
    SECTION("an intact entry holding garbage is refused by the driver") {
        std::vector<unsigned char> garbage(4096);
        for (std::size_t i = 0; i < garbage.size(); ++i)
            garbage[i] = static_cast<unsigned char>(i * 131 + 7);
        std::string name = std::filesystem::path(first.cache_file).stem().string();
        std::uint64_t key = std::stoull(name, nullptr, 16);
        const std::string text =
            program_cache_key_text(expand_includes(add_kernel(), "add.cl"), kOptions,
                                   device_cache_identity(test::device().info.device));
        test::write_bytes(first.cache_file, ProgramCache::encode(key, text, garbage));
        BuiltProgram rebuilt = build_add(dir.path());
        CHECK(rebuilt.cache == CacheOutcome::Rejected);
        CHECK(rebuilt.cache_note == "the driver rejected the cached binary");
        CHECK(run_add(rebuilt.program) == kAdded);
    }
    SECTION("an intact entry under this key built with other options") {
        // The other build's own binary, its hash rewritten to this key's:
        // only the stored key text tells them apart.
        test::TempDir other;
        BuiltProgram donor = build_add(other.path(), add_kernel(), kOptions + " -D UNUSED=3");
        std::vector<unsigned char> foreign = test::read_bytes(donor.cache_file);
        const std::string name = std::filesystem::path(first.cache_file).stem().string();
        const std::uint64_t key = std::stoull(name, nullptr, 16);
        for (int i = 0; i < 8; ++i)
            foreign[16 + static_cast<std::size_t>(i)] = static_cast<unsigned char>(key >> (8 * i));
        test::write_bytes(first.cache_file, foreign);
        BuiltProgram rebuilt = build_add(dir.path());
        CHECK(rebuilt.cache == CacheOutcome::Rejected);
        CHECK(rebuilt.cache_note == "its stored key is for other options");
        CHECK(run_add(rebuilt.program) == kAdded);
    }
    SECTION("a stale format version") {
        bytes[8] = static_cast<unsigned char>(kProgramCacheFormat + 1);
        test::write_bytes(first.cache_file, bytes);
        BuiltProgram rebuilt = build_add(dir.path());
        CHECK(rebuilt.cache == CacheOutcome::Rejected);
        CHECK(rebuilt.cache_note.find("format version") != std::string::npos);
    }
    CHECK(build_add(dir.path()).cache == CacheOutcome::Hit);
    CHECK(entry_files(dir).size() == 1);
}

TEST_CASE("program cache: off it writes nothing, and an unwritable one stops no build") {
    test::TempDir dir;
    DeviceContext& device = test::device();
    BuiltProgram off = build_program(device.context, device.info.device, add_kernel(), "add.cl",
                                     kOptions, CachePolicy::off());
    CHECK(off.cache == CacheOutcome::Off);
    CHECK(off.cache_file.empty());
    CHECK(entry_files(dir).empty());

    // A cache "directory" that is a file: nothing can be stored.
    test::write_text(dir / "not-a-directory", "x");
    BuiltProgram unwritable = build_add(dir / "not-a-directory");
    CHECK(unwritable.cache == CacheOutcome::Miss);
    CHECK(unwritable.cache_note.find("not stored") != std::string::npos);
    CHECK(run_add(unwritable.program) == kAdded);
}

TEST_CASE("program cache: the wavefront program goes through the cache by default") {
    test::TempDir dir;
    DeviceContext& device = test::device();
    EnvGuard own("WAVEPATH_CACHE_DIR", nullptr);
    EnvGuard xdg("XDG_CACHE_HOME", dir.path().c_str());
    EnvGuard on("WAVEPATH_NO_CACHE", nullptr);
    // On PoCL the driver's own kernel cache stands in for ours, unless it is off.
    EnvGuard pocl_cache("POCL_KERNEL_CACHE", "0");
    REQUIRE_FALSE(driver_keeps_kernel_cache(device.info.device));
    BuiltProgram first = build_wavefront_program(device.context, device.info.device, "");
    CHECK(first.cache == CacheOutcome::Miss);
    CHECK(first.cache_file.rfind((dir.path() / "wavepath").string(), 0) == 0);
    BuiltProgram second = build_wavefront_program(device.context, device.info.device, "");
    CHECK(second.cache == CacheOutcome::Hit);
    for (const char* name : {"generate", "intersect", "shade", "shadow", "accumulate"})
        CHECK_NOTHROW(cl::Kernel(second.program, name));

    // Another program's binary under the wavefront's key, with a valid
    // checksum (a copied or crafted entry): dropped and rebuilt, not used.
    test::TempDir donor_dir;
    std::vector<unsigned char> foreign = test::read_bytes(build_add(donor_dir.path()).cache_file);
    foreign.erase(foreign.begin(),
                  foreign.begin() + static_cast<std::ptrdiff_t>(entry_header_size(foreign)));
    ProgramCache cache(dir.path() / "wavepath");
    const std::uint64_t key =
        program_cache_key(expand_includes(wavefront_program_source(), "wavefront.cl"), "",
                          device_cache_identity(device.info.device));
    REQUIRE(cache.entry_path(key).string() == second.cache_file);
    const std::string text =
        program_cache_key_text(expand_includes(wavefront_program_source(), "wavefront.cl"), "",
                               device_cache_identity(device.info.device));
    REQUIRE(cache.store(key, text, foreign).empty());
    BuiltProgram third = build_wavefront_program(device.context, device.info.device, "");
    CHECK(third.cache == CacheOutcome::Rejected);
    CHECK(third.cache_note.find("lacked the kernel") != std::string::npos);
    for (const char* name : {"generate", "intersect", "shade", "shadow", "accumulate"})
        CHECK_NOTHROW(cl::Kernel(third.program, name));
    CHECK(build_wavefront_program(device.context, device.info.device, "").cache ==
          CacheOutcome::Hit); // the rebuilt program was stored again

    EnvGuard off("WAVEPATH_NO_CACHE", "1");
    CHECK(build_wavefront_program(device.context, device.info.device, "").cache ==
          CacheOutcome::Off);
}

TEST_CASE("program cache: on PoCL the wavefront program is left to PoCL's own kernel cache") {
    DeviceContext& device = test::device();
    if (device.info.platform_name.find("Portable Computing Language") == std::string::npos) {
        WARN("skipped: the test device is not PoCL");
        return;
    }
    test::TempDir dir;
    EnvGuard pocl_cache("POCL_KERNEL_CACHE", nullptr);
    CHECK(driver_keeps_kernel_cache(device.info.device));
    BuiltProgram built = build_wavefront_program(device.context, device.info.device, "",
                                                 CachePolicy::in(dir.path()));
    CHECK(built.cache == CacheOutcome::Driver);
    CHECK(built.cache_file.empty());
    CHECK_FALSE(built.cache_note.empty());
    CHECK(std::filesystem::is_empty(dir.path())); // no binary asked for, none stored
    for (const char* name : {"generate", "intersect", "shade", "shadow", "accumulate", "wave"})
        CHECK_NOTHROW(cl::Kernel(built.program, name));
}
