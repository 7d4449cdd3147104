// Compiling the embedded OpenCL C sources for one device.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cl/cl.hpp"
#include "cl/program_cache.hpp"

namespace wp {

// A kernel build that failed. what() is one line; log() is the compiler's
// output, whose diagnostics name the kernel file and line (see expand_includes).
class BuildError : public std::runtime_error {
  public:
    BuildError(const std::string& message, std::string log)
        : std::runtime_error(message), log_(std::move(log)) {}
    const std::string& log() const { return log_; }

  private:
    std::string log_;
};

// The text of an embedded kernel file, e.g. "shade.cl". Throws std::out_of_range.
std::string_view kernel_file(std::string_view name);

// Source text with every `#include "file"` replaced by that embedded file
// (each file once), framed by #line directives so that the compiler's
// diagnostics name the original file and line.
std::string expand_includes(std::string_view text, std::string_view name);

// `log` with every location given as a line of the expanded text, as
// NVIDIA's compiler gives them ("<kernel>:318:14: error: ..."; it ignores
// #line), rewritten as the original file and line ("broken.cl:3:14: ...")
// from expand_includes' #line markers. Other locations are left as they are.
std::string log_with_source_lines(const std::string& log, std::string_view expanded);

// How a build went with the program cache.
enum class CacheOutcome {
    Off,      // the cache was not used
    Miss,     // no entry: built from source and stored (cache_note says if it could not be)
    Hit,      // loaded from a cached binary
    Rejected, // an entry was damaged, stale or refused by the driver: removed, rebuilt, stored
    Driver,   // left to the driver's own kernel cache (driver_keeps_kernel_cache)
};

// "off", "miss", "hit", "rejected", "driver"
const char* cache_outcome_name(CacheOutcome outcome);

struct BuiltProgram {
    cl::Program program;
    std::string options;
    double build_seconds = 0.0; // wall time from source text to a built program
    CacheOutcome cache = CacheOutcome::Off;
    bool cache_hit = false; // cache == CacheOutcome::Hit
    std::string cache_file; // the entry used or written; empty with the cache off
    std::string cache_note; // why an entry was rejected, or could not be stored
};

// Builds `source` (which may include embedded kernel headers) with `options`.
// Throws BuildError with the compiler log when the build fails. With the
// cache on, a valid cached binary for the same expanded source, options and
// device is loaded instead of compiling, and a fresh build is stored.
BuiltProgram build_program(const cl::Context& context, const cl::Device& device,
                           std::string_view source, std::string_view source_name,
                           const std::string& options,
                           const CachePolicy& cache = CachePolicy::off());

// The text build_wavefront_program compiles (before include expansion).
std::string_view wavefront_program_source();

// Whether the device's driver keeps a kernel cache of its own that serves a
// second build of the same source and options, and that a binary from ours
// would only slow down: PoCL, unless POCL_KERNEL_CACHE=0 turns its cache off.
// Asked for a program's binary, PoCL first compiles every kernel in it for
// any work-group size, the fused kernels that a launch plan never launches
// among them (the hexroom's program: 22 s of processor time instead of 5.7 s);
// a second build from source then finds its own cache (0.2 s, faster than
// loading our binary). wavepath points PoCL's cache into its own directory
// and bounds it (app/caches.cpp).
bool driver_keeps_kernel_cache(const cl::Device& device);

// Every wavefront kernel (the stages, the fused kernels, mirror_shadow) in one
// program, through the program cache unless WAVEPATH_NO_CACHE is set
// (CachePolicy::from_environment()) or the driver keeps its own
// (CacheOutcome::Driver). A cached binary that lacks one of the stages' kernels
// is removed and rebuilt, with a warning on stderr (cache: Rejected,
// cache_note says which kernel).
BuiltProgram build_wavefront_program(const cl::Context& context, const cl::Device& device,
                                     const std::string& options);
BuiltProgram build_wavefront_program(const cl::Context& context, const cl::Device& device,
                                     const std::string& options, const CachePolicy& cache);

} // namespace wp
