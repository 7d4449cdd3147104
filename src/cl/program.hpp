// Compiling the embedded OpenCL C sources for one device.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cl/cl.hpp"

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

struct BuiltProgram {
    cl::Program program;
    std::string options;
    double build_seconds = 0.0;
};

// Builds `source` (which may include embedded kernel headers) with `options`.
// Throws BuildError with the compiler log when the build fails.
BuiltProgram build_program(const cl::Context& context, const cl::Device& device,
                           std::string_view source, std::string_view source_name,
                           const std::string& options);

// The five wavefront stages in one program.
BuiltProgram build_wavefront_program(const cl::Context& context, const cl::Device& device,
                                     const std::string& options);

} // namespace wp
