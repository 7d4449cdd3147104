#include "cl/program.hpp"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>

#include "cl/embedded_kernels.hpp"
#include "cl/error.hpp"
#include "cl/stages.hpp"

namespace wp {
namespace {

void expand_into(std::string_view text, std::string_view name, std::set<std::string>& included,
                 std::string& out) {
    out += "#line 1 \"" + std::string(name) + "\"\n";
    std::size_t line_number = 0;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos)
            end = text.size();
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;

        std::size_t hash = line.find_first_not_of(" \t");
        bool is_include = hash != std::string_view::npos && line.substr(hash, 1) == "#" &&
                          line.find("include", hash) != std::string_view::npos;
        std::size_t open = line.find('"');
        std::size_t close = open == std::string_view::npos ? open : line.find('"', open + 1);
        if (!is_include || close == std::string_view::npos) {
            out.append(line);
            out += '\n';
            continue;
        }
        std::string header(line.substr(open + 1, close - open - 1));
        if (included.insert(header).second)
            expand_into(kernel_file(header), header, included, out);
        out += "#line " + std::to_string(line_number + 1) + " \"" + std::string(name) + "\"\n";
    }
}

// The binary of a program built for `device` (one of its context's devices).
std::vector<unsigned char> program_binary(const cl::Program& program, const cl::Device& device) {
    std::vector<cl::Device> devices = program.getInfo<CL_PROGRAM_DEVICES>();
    cl::Program::Binaries binaries = program.getInfo<CL_PROGRAM_BINARIES>();
    for (std::size_t i = 0; i < devices.size() && i < binaries.size(); ++i)
        if (devices[i]() == device())
            return binaries[i];
    return {};
}

// A program from a cached binary, built with the same options; nothing if the
// driver refuses the binary (another driver version, a damaged file that
// passed the checksum, ...).
std::optional<cl::Program> load_binary(const cl::Context& context, const cl::Device& device,
                                       const std::vector<unsigned char>& binary,
                                       const std::string& options) {
    try {
        std::vector<cl_int> status;
        cl::Program program(context, {device}, cl::Program::Binaries{binary}, &status);
        if (status.empty() || status[0] != CL_SUCCESS)
            return std::nullopt;
        program.build({device}, options.c_str());
        if (program.getBuildInfo<CL_PROGRAM_BUILD_STATUS>(device) != CL_BUILD_SUCCESS)
            return std::nullopt;
        return program;
    } catch (const cl::Error&) {
        return std::nullopt;
    }
}

} // namespace

std::string_view kernel_file(std::string_view name) {
    for (const EmbeddedFile& file : embedded_kernel_files())
        if (file.name == name)
            return file.text;
    throw std::out_of_range("no embedded kernel file named '" + std::string(name) + "'");
}

std::string expand_includes(std::string_view text, std::string_view name) {
    std::set<std::string> included;
    std::string out;
    expand_into(text, name, included, out);
    return out;
}

std::string log_with_source_lines(const std::string& log, std::string_view expanded) {
    // origin[n]: the file and line of the expanded text's line n (1-based).
    std::vector<std::string> origin(1);
    std::string file = "?";
    std::size_t line = 1;
    std::size_t start = 0;
    while (start < expanded.size()) {
        std::size_t end = expanded.find('\n', start);
        if (end == std::string_view::npos)
            end = expanded.size();
        std::string_view text = expanded.substr(start, end - start);
        start = end + 1;
        origin.push_back(file + ":" + std::to_string(line));
        if (text.rfind("#line ", 0) == 0) {
            std::size_t open = text.find('"'), close = text.rfind('"');
            if (open != std::string_view::npos && close > open) {
                line = std::strtoul(std::string(text.substr(6)).c_str(), nullptr, 10);
                file = std::string(text.substr(open + 1, close - open - 1));
                continue;
            }
        }
        ++line;
    }
    std::string out;
    std::size_t at = 0;
    while (at < log.size()) {
        std::size_t found = log.find('<', at);
        if (found == std::string::npos)
            break;
        std::size_t digits = std::string::npos;
        for (const char* marker : {"<kernel>:", "<source>:"})
            if (log.compare(found, std::strlen(marker), marker) == 0)
                digits = found + std::strlen(marker);
        std::size_t after =
            digits == std::string::npos ? digits : log.find_first_not_of("0123456789", digits);
        if (digits == std::string::npos || after == digits) {
            out.append(log, at, found + 1 - at);
            at = found + 1;
            continue;
        }
        const std::size_t n = std::strtoul(log.substr(digits, after - digits).c_str(), nullptr, 10);
        out.append(log, at, found - at);
        out += n < origin.size() ? origin[n] : log.substr(found, after - found);
        at = after;
    }
    if (at < log.size())
        out.append(log, at, std::string::npos);
    return out;
}

const char* cache_outcome_name(CacheOutcome outcome) {
    switch (outcome) {
    case CacheOutcome::Off:
        return "off";
    case CacheOutcome::Miss:
        return "miss";
    case CacheOutcome::Hit:
        return "hit";
    case CacheOutcome::Rejected:
        return "rejected";
    case CacheOutcome::Driver:
        return "driver";
    }
    return "?";
}

namespace {

// WAVEPATH_PROGRAM_LOG=FILE appends one line per program build asked for:
// a hash of the expanded source and options, the source's name, the options
// and the process's arguments (a test case's name under ctest), so that a suite run
// counts the distinct programs each test compiles (tools/program-census,
// docs/testing.md). A cold suite's time is mostly those compiles.
void log_program_request(std::string_view source_name, const std::string& expanded,
                         const std::string& options) {
    const char* path = std::getenv("WAVEPATH_PROGRAM_LOG");
    if (path == nullptr || *path == '\0')
        return;
    std::string process;
    if (std::ifstream cmdline("/proc/self/cmdline", std::ios::binary); cmdline) {
        std::string argument;
        while (std::getline(cmdline, argument, '\0'))
            process += (process.empty() ? "" : " ") + argument;
    }
    const std::size_t program = std::hash<std::string>{}(expanded + '\n' + options);
    std::ofstream(path, std::ios::app)
        << std::hex << program << '\t' << source_name << '\t' << options << '\t' << process << '\n';
}

} // namespace

// Options a device needs besides the caller's.
//  - Division and square root correctly rounded wherever the device can: by
//    default OpenCL allows 2.5 and 3 ulps, which NVIDIA's compiler uses, and
//    the sphere test's roots (sphere.h) then put a small far sphere's hit
//    point off by a tenth of its radius along the ray: on the H200 the
//    stability case sphere-far-small came out 2.2 % darker than PoCL's image
//    and the analytic value, its rim 20 % (docs/gpu.md). CPU devices round
//    these correctly anyway.
//  - Oclgrind (the simulator of .ci/oclgrind-check) cannot run
//    llvm.bitreverse, which clang makes of sobol.h's bit reversal; there
//    sobol.h reverses through a table instead (the same bits).
std::string device_workaround_options(const cl::Device& device) {
    std::string options;
    if (device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT)
        options += " -cl-fp32-correctly-rounded-divide-sqrt";
    const cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>());
    if (platform.getInfo<CL_PLATFORM_NAME>().find("Oclgrind") != std::string::npos)
        options += " -D WP_BIT_REVERSAL_TABLE=1";
    return options;
}

BuiltProgram build_program(const cl::Context& context, const cl::Device& device,
                           std::string_view source, std::string_view source_name,
                           const std::string& caller_options, const CachePolicy& cache) {
    // The workarounds depend on the device alone, which the cache key holds
    // already: the key and the reported options are the caller's.
    const std::string options = caller_options + device_workaround_options(device);
    auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    std::string expanded = expand_includes(source, source_name);
    log_program_request(source_name, expanded, options);
    BuiltProgram built;
    built.options = caller_options;

    std::optional<ProgramCache> store;
    std::uint64_t key = 0;
    std::string key_text;
    if (cache.enabled) {
        std::filesystem::path dir =
            cache.directory.empty() ? default_program_cache_directory() : cache.directory;
        if (dir.empty()) {
            built.cache_note = "no cache directory (neither XDG_CACHE_HOME nor HOME is set)";
        } else {
            store.emplace(dir);
            const std::string identity = device_cache_identity(device);
            key = program_cache_key(expanded, caller_options, identity);
            key_text = program_cache_key_text(expanded, caller_options, identity);
            built.cache_file = store->entry_path(key).string();
            CacheLookup found = store->load(key, key_text);
            if (found.binary) {
                if (std::optional<cl::Program> loaded =
                        load_binary(context, device, *found.binary, options)) {
                    built.program = std::move(*loaded);
                    built.cache = CacheOutcome::Hit;
                    built.cache_hit = true;
                    built.build_seconds = elapsed();
                    return built;
                }
                store->remove(key);
                found.rejected = "the driver rejected the cached binary";
            }
            built.cache = found.rejected.empty() ? CacheOutcome::Miss : CacheOutcome::Rejected;
            built.cache_note = found.rejected;
        }
    }

    built.program = cl::Program(context, expanded);
    try {
        built.program.build({device}, options.c_str());
    } catch (const cl::Error& error) {
        std::string log;
        try {
            log = built.program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
        } catch (const cl::Error&) {
            log = "(the driver gave no build log)";
        }
        throw BuildError("OpenCL kernel build of '" + std::string(source_name) + "' failed (" +
                             cl_error_name(error.err()) + ") on " +
                             device.getInfo<CL_DEVICE_NAME>() + ", driver " +
                             device.getInfo<CL_DRIVER_VERSION>() + "; the compiler log is above",
                         log_with_source_lines(log, expanded));
    }
    built.build_seconds = elapsed();

    if (store) {
        std::vector<unsigned char> binary = program_binary(built.program, device);
        std::string failure = binary.empty() ? std::string("the driver gave no binary")
                                             : store->store(key, key_text, binary);
        if (!failure.empty())
            built.cache_note += (built.cache_note.empty() ? "" : "; ") + ("not stored: " + failure);
    }
    return built;
}

std::string_view wavefront_program_source() {
    // One translation unit with every stage: the shared headers compile once.
    static const std::string source = [] {
        std::string text;
        for (std::string_view stage : kStageKernelNames)
            text += "#include \"" + std::string(stage) + ".cl\"\n";
        return text;
    }();
    return source;
}

BuiltProgram build_wavefront_program(const cl::Context& context, const cl::Device& device,
                                     const std::string& options) {
    return build_wavefront_program(context, device, options, CachePolicy::from_environment());
}

bool driver_keeps_kernel_cache(const cl::Device& device) {
    const cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>());
    if (platform.getInfo<CL_PLATFORM_NAME>().find("Portable Computing Language") ==
        std::string::npos)
        return false;
    const char* pocl_cache = std::getenv("POCL_KERNEL_CACHE");
    return pocl_cache == nullptr || std::string_view(pocl_cache) != "0";
}

BuiltProgram build_wavefront_program(const cl::Context& context, const cl::Device& device,
                                     const std::string& options, const CachePolicy& cache) {
    if (cache.enabled && driver_keeps_kernel_cache(device)) {
        BuiltProgram built = build_program(context, device, wavefront_program_source(),
                                           "wavefront.cl", options, CachePolicy::off());
        built.cache = CacheOutcome::Driver;
        built.cache_note = "PoCL's own kernel cache serves it (a binary would compile every "
                           "kernel first)";
        return built;
    }
    BuiltProgram built =
        build_program(context, device, wavefront_program_source(), "wavefront.cl", options, cache);
    if (!built.cache_hit)
        return built;
    // A cached entry is named and checked by its key and checksum, but its
    // payload could still be another program's (a copied or crafted file):
    // one without every stage would fail each render with
    // CL_INVALID_KERNEL_NAME. Dropped and rebuilt, with a word of why.
    // ";a;b;" and ";name;", appended piecewise: `";" + std::string` trips a
    // GCC 12 -Wrestrict false positive.
    std::string listed = ";";
    try {
        listed.append(built.program.getInfo<CL_PROGRAM_KERNEL_NAMES>().c_str());
    } catch (const cl::Error&) {
    }
    listed.append(";");
    for (std::string_view stage : kStageKernelNames) {
        std::string wanted = ";";
        wanted.append(stage).append(";");
        if (listed.find(wanted) != std::string::npos)
            continue;
        std::cerr << "wavepath: warning: the cached kernels '" << built.cache_file
                  << "' lack the kernel '" << stage << "': removed and rebuilt\n";
        std::error_code ec;
        std::filesystem::remove(built.cache_file, ec);
        BuiltProgram rebuilt = build_program(context, device, wavefront_program_source(),
                                             "wavefront.cl", options, cache);
        rebuilt.cache = CacheOutcome::Rejected;
        rebuilt.cache_note = "the cached binary lacked the kernel '" + std::string(stage) + "'";
        return rebuilt;
    }
    return built;
}

} // namespace wp
