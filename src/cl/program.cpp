#include "cl/program.hpp"

#include <chrono>
#include <set>
#include <sstream>

#include "cl/embedded_kernels.hpp"
#include "cl/error.hpp"

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

BuiltProgram build_program(const cl::Context& context, const cl::Device& device,
                           std::string_view source, std::string_view source_name,
                           const std::string& options) {
    std::string expanded = expand_includes(source, source_name);
    BuiltProgram built{cl::Program(context, expanded), options, 0.0};
    auto start = std::chrono::steady_clock::now();
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
                             cl_error_name(error.err()) + "); the compiler log is above",
                         log);
    }
    built.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return built;
}

BuiltProgram build_wavefront_program(const cl::Context& context, const cl::Device& device,
                                     const std::string& options) {
    // One translation unit with every stage: the shared headers compile once.
    static constexpr const char* stages =
        "#include \"generate.cl\"\n#include \"intersect.cl\"\n#include \"shade.cl\"\n"
        "#include \"shadow.cl\"\n#include \"accumulate.cl\"\n";
    return build_program(context, device, stages, "wavefront.cl", options);
}

} // namespace wp
