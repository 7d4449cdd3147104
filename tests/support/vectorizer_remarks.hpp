// PoCL's loop-vectoriser remarks for wavepath's stage kernels, so that a test
// can say whether a stage's work-item loop was vectorised.
//
// PoCL runs every work-item of a work-group in one loop per kernel and hands
// that loop to LLVM's loop vectoriser, which vectorises it only if every
// instruction in it can be widened (docs/specialization.md, "What it takes to
// get the probe's gain"). With POCL_VECTORIZER_REMARKS=1 it prints LLVM's
// remarks to stdout at build time, without a function name
// ("<unknown>:0:0: loop not vectorized: ..."), and the build happens at a
// kernel's first launch. So the remarks are captured from a child process
// (the variable is read once per process) that renders a small image with
// both program caches off, and are split by kernel at the line where PoCL
// inlines the kernel into its work-group function
// ("'_pocl_kernel_shade' inlined into '_pocl_kernel_shade_workgroup'"):
// that kernel's work-group loop remarks follow it. A kernel's own inner loops
// are optimised just before its marker, so they are counted with the kernel
// built before it; a test should therefore ask about the work-group loop only.
//
//     if (!test_device_is_pocl()) { WARN("skipped: ..."); return; }
//     VectorizerRemarks r = capture_vectorizer_remarks(WAVEPATH_SOURCE_DIR "/scenes/hexroom.json");
//     REQUIRE(r.captured);
//     CHECK(r.vectorized("shade"));
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "cl/stages.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace wp::test {

// Whether the test device is PoCL's, the one OpenCL whose remarks these are.
inline bool test_device_is_pocl() {
    return device_info().platform_name.find("Portable Computing Language") != std::string::npos;
}

struct VectorizerRemarks {
    bool captured = false;          // false: the render failed or printed no remarks
    std::vector<std::string> lines; // every remark, in build order

    // The remarks from `kernel`'s work-group marker up to the next kernel's
    // marker (empty if the kernel was never built).
    // A remark that names another kernel ('shade', '_pocl_kernel_shade...')
    // ends the range too.
    std::vector<std::string> of_kernel(std::string_view kernel) const {
        const std::string own = "'_pocl_kernel_" + std::string(kernel) + "' inlined into";
        std::vector<std::string> out;
        bool inside = false;
        for (const std::string& line : lines) {
            const bool marker = line.rfind("'_pocl_kernel_", 0) == 0 &&
                                line.find("_workgroup'") != std::string::npos;
            if (marker)
                inside = line.rfind(own, 0) == 0;
            else if (inside && names_another_kernel(line, kernel))
                inside = false;
            if (inside)
                out.push_back(line);
        }
        return out;
    }

    static bool names_another_kernel(const std::string& line, std::string_view kernel) {
        for (std::string_view other : kStageKernelNames) {
            if (other == kernel)
                continue;
            std::string quoted(1, '\''), work_group("'_pocl_kernel_");
            quoted.append(other).push_back('\'');
            work_group.append(other);
            if (line.find(quoted) != std::string::npos ||
                line.find(work_group) != std::string::npos)
                return true;
        }
        return false;
    }

    // Whether LLVM vectorised a loop of `kernel` ("vectorized loop (...").
    bool vectorized(std::string_view kernel) const {
        return !matching(kernel, "vectorized loop").empty();
    }

    // The remarks of `kernel` that contain `text`, e.g. "loop not vectorized".
    std::vector<std::string> matching(std::string_view kernel, std::string_view text) const {
        std::vector<std::string> out;
        for (const std::string& line : of_kernel(kernel))
            if (line.find(text) != std::string::npos)
                out.push_back(line);
        return out;
    }
};

// Renders `scene` at 8x8, 1 spp with the wavepath executable on the test
// device (support/test_device.hpp) and returns the
// vectoriser remarks of its kernels. `options` are more render options (e.g.
// "--general").
inline VectorizerRemarks capture_vectorizer_remarks(const std::string& scene,
                                                    const std::string& options = "") {
    const TempDir dir;
    const std::filesystem::path out = dir / "stdout.txt";
    const std::string command =
        "WAVEPATH_DEVICE='" + device_info().index_string() +
        "' WAVEPATH_NO_CACHE=1 POCL_KERNEL_CACHE=0 POCL_VECTORIZER_REMARKS=1 '" +
        std::string(WAVEPATH_EXE) + "' render '" + scene + "' --width 8 --height 8 --spp 1 -o '" +
        (dir / "x.exr").string() + "' " + options + " >'" + out.string() + "' 2>/dev/null";
    VectorizerRemarks remarks;
    if (std::system(command.c_str()) != 0)
        return remarks;
    std::ifstream in(out);
    std::stringstream text;
    text << in.rdbuf();
    // Remarks are run together without newlines: split at each location prefix.
    const std::string all = text.str(), prefix = "<unknown>:0:0: ";
    for (std::size_t at = all.find(prefix); at != std::string::npos;) {
        const std::size_t next = all.find(prefix, at + prefix.size());
        std::string line =
            all.substr(at + prefix.size(),
                       next == std::string::npos ? std::string::npos : next - at - prefix.size());
        if (const std::size_t end = line.find('\n'); end != std::string::npos)
            line.resize(end); // the render's own output follows the last remark
        remarks.lines.push_back(line);
        at = next;
    }
    remarks.captured = !remarks.lines.empty();
    return remarks;
}

} // namespace wp::test
