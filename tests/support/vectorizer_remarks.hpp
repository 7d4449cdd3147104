// What PoCL's vectoriser said about one stage kernel of a scene's program.
//
// PoCL prints LLVM's optimisation remarks when POCL_VECTORIZER_REMARKS=1 is
// set at build time (to stdout, without newlines, each starting
// "<unknown>:0:0: "). They name no kernel, but the work-group function of
// kernel K is generated from "'_pocl_kernel_K' inlined into
// '_pocl_kernel_K_workgroup'", so the remarks from there to the first one
// that names another function's kernel are K's: its work-group loop's
// "vectorized loop (vectorization width: 8, ...)" or "loop not vectorized:
// <why>".
//
// The remarks come only from a real build, so the scene is rendered (8x8, 1
// spp) by a child wavepath process with both caches off: wavepath's program
// cache (WAVEPATH_NO_CACHE) and PoCL's kernel cache (POCL_KERNEL_CACHE=0).
// Needs WAVEPATH_EXE (the app, kernels, render, cl and stability tests have it).
#pragma once

#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "app/cli_run.hpp"
#include "cl/stages.hpp"
#include "support/test_device.hpp"

namespace wp::test {

// True when the tests run on PoCL, the only device whose vectoriser we read.
inline bool test_device_is_pocl() {
    return device_info().platform_name.find("Portable Computing Language") != std::string::npos;
}

// Every remark of one build of `scene` (a path) with the render's extra
// `options` (e.g. "--general"), one per line; memoised, since one build
// reports on all stages.
inline const std::string& vectorizer_remarks_of_build(const std::string& scene,
                                                      const std::string& options) {
    static std::map<std::string, std::string>& builds = *new std::map<std::string, std::string>;
    const std::string key = scene + '\n' + options;
    auto found = builds.find(key);
    if (found != builds.end())
        return found->second;
    cli::Scratch scratch;
    cli::Run run =
        cli::wavepath("render '" + scene + "' --width 8 --height 8 --spp 1 -o '" +
                          (scratch.dir / "remarks.exr").string() + "' " + options,
                      scratch, "POCL_VECTORIZER_REMARKS=1 POCL_KERNEL_CACHE=0 WAVEPATH_NO_CACHE=1");
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    std::string lines, all = run.out + run.err;
    const std::string_view mark = "<unknown>:0:0: ";
    for (std::size_t at = all.find(mark); at != std::string::npos;) {
        std::size_t next = all.find(mark, at + mark.size());
        std::string_view remark = std::string_view(all).substr(
            at + mark.size(), (next == std::string::npos ? all.size() : next) - at - mark.size());
        while (!remark.empty() && (remark.back() == '\n' || remark.back() == '\r'))
            remark.remove_suffix(1);
        lines.append(remark).push_back('\n');
        at = next;
    }
    return builds.emplace(key, lines).first->second;
}

// The remarks about the work-group function of stage kernel `stage` (e.g.
// "intersect") in the program built for `scene` (with the render's extra
// `options`), one per line; empty if the build reported nothing for it.
inline std::string vectorizer_remarks_for(const std::string& scene, std::string_view stage,
                                          const std::string& options = "") {
    // "'_pocl_kernel_NAME" and "'NAME'": how a remark names kernel NAME.
    auto work_group_mark = [](std::string_view name) {
        std::string mark = "'_pocl_kernel_";
        mark.append(name);
        return mark;
    };
    auto kernel_mark = [](std::string_view name) {
        std::string mark = "'";
        mark.append(name).push_back('\'');
        return mark;
    };
    std::string start = work_group_mark(stage);
    start.append("' inlined into ").append(work_group_mark(stage)).append("_workgroup");
    std::vector<std::string> others;
    for (std::string_view name : kStageKernelNames)
        if (name != stage) {
            others.push_back(work_group_mark(name));
            others.push_back(kernel_mark(name));
        }
    std::istringstream lines(vectorizer_remarks_of_build(scene, options));
    std::string line, remarks;
    bool inside = false;
    while (std::getline(lines, line)) {
        if (line.find(start) != std::string::npos) {
            inside = true;
            continue;
        }
        if (!inside)
            continue;
        // Another kernel's remark ends this one's: it names that kernel or its
        // work-group function ('shade', '_pocl_kernel_shade...').
        bool other = false;
        for (const std::string& mark : others)
            other = other || line.find(mark) != std::string::npos;
        if (other)
            break;
        remarks += line;
        remarks += '\n';
    }
    return remarks;
}

} // namespace wp::test
