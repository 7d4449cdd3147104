// wavepath: a wavefront Monte Carlo path tracer on OpenCL.
//
// This file only parses the command line and turns every failure into one
// line on stderr and a non-zero exit; the subcommands live in commands.cpp,
// bench.cpp, converge.cpp, compare.cpp, info.cpp and export_mitsuba.cpp.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/breakdown.hpp"
#include "app/caches.hpp"
#include "app/commands.hpp"
#include "app/interrupt.hpp"
#include "cl/device.hpp"
#include "cl/error.hpp"
#include "cl/program.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"
#include "util/file.hpp"
#include "util/suggest.hpp"

namespace {

// The one-line message for a first argument that is no subcommand, with the
// nearest name if there is one ("unknown subcommand 'rendr'; did you mean
// 'render'?"); empty when the first argument is an option or a subcommand.
std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
    if (argc < 2 || argv[1][0] == '-')
        return {};
    const std::string typed = argv[1];
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) {
        if (sub->get_name() == typed)
            return {};
        if (!sub->get_group().empty()) // hidden ones are for scripts, not to be suggested
            names.push_back(sub->get_name());
    }
    std::string list;
    for (const std::string& name : names)
        list += (list.empty() ? "" : ", ") + name;
    const auto nearest = wp::nearest_name(typed, names);
    return "unknown subcommand '" + typed + "'; " +
           (nearest ? "did you mean '" + *nearest + "'?" : "expected one of " + list);
}

// Output that never arrived is a failure too ("wavepath devices > /dev/full"):
// flush stdout and report the first error its writes met.
int finish_stdout(int status) {
    errno = 0;
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::cerr << "wavepath: error: cannot write to standard output: "
                  << wp::errno_text(errno != 0 ? errno : EIO) << "\n";
        return status == 0 ? 1 : status;
    }
    return status;
}

} // namespace

int main(int argc, char** argv) {
    // PoCL aborts on a POCL_CACHE_DIR that is set but empty (an assertion in
    // its cache set-up), which an environment such as `POCL_CACHE_DIR= ...`
    // makes; empty means "not chosen", as for wavepath's own variables.
    if (const char* pocl_cache = std::getenv("POCL_CACHE_DIR");
        pocl_cache != nullptr && *pocl_cache == '\0')
        ::unsetenv("POCL_CACHE_DIR");

    CLI::App app{"wavepath: a wavefront Monte Carlo path tracer on OpenCL"};
    app.require_subcommand(1);

    bool check_devices = false;
    app.add_subcommand("devices", "List every OpenCL platform and device")
        ->add_flag("--check", check_devices,
                   "Also check each device's specialised kernels against its general ones "
                   "(docs/gpu.md); exit status 1 if one disagrees");

    wp::RenderCommand render;
    wp::add_render_subcommand(app, render);
    wp::BenchCommand bench;
    wp::add_bench_subcommand(app, bench);
    // Convergence reports (converge.cpp, compare.cpp; docs/convergence.md).
    wp::ConvergeCommand converge;
    wp::CompareCommand compare;
    CLI::App* converge_app = wp::add_converge_subcommand(app, converge);
    CLI::App* compare_app = wp::add_compare_subcommand(app, compare);
    wp::InfoCommand info;
    CLI::App* info_app = wp::add_info_subcommand(app, info);
    wp::KernelSourceCommand kernel_source; // hidden: for .ci/gpu-targets-check
    CLI::App* kernel_source_app = wp::add_kernel_source_subcommand(app, kernel_source);
    wp::ExportMitsubaCommand export_mitsuba;
    CLI::App* export_app = wp::add_export_mitsuba_subcommand(app, export_mitsuba);
    wp::BreakdownCommand breakdown; // where the error is (breakdown.cpp)
    CLI::App* breakdown_app = wp::add_breakdown_subcommand(app, breakdown);

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) { // --help
        return finish_stdout(app.exit(e));
    } catch (const CLI::ParseError& e) {
        const std::string unknown = unknown_subcommand(app, argc, argv);
        std::cerr << "wavepath: error: " << (unknown.empty() ? e.what() : unknown)
                  << " (see wavepath --help)\n";
        return 2;
    }

    // Only render stops at a wave boundary; elsewhere Ctrl-C keeps its
    // default, immediate effect.
    if (app.got_subcommand("render"))
        wp::install_interrupt_handlers();
    int status = 1;
    try {
        if (app.got_subcommand("bench"))
            wp::prepare_caches(bench.integrator);
        else if (converge_app->parsed())
            wp::prepare_caches(converge.integrator);
        else if (info_app->parsed())
            wp::prepare_caches(info.integrator);
        else if (breakdown_app->parsed())
            wp::prepare_caches(breakdown.integrator);
        else if (app.got_subcommand("render"))
            wp::prepare_caches(render.integrator);
        if (app.got_subcommand("devices"))
            status = wp::run_devices(check_devices);
        else if (app.got_subcommand("bench"))
            status = wp::run_bench(bench);
        else if (converge_app->parsed())
            status = wp::run_converge(converge);
        else if (compare_app->parsed())
            status = wp::run_compare(compare);
        else if (info_app->parsed())
            status = wp::run_info(info);
        else if (kernel_source_app->parsed())
            status = wp::run_kernel_source(kernel_source);
        else if (export_app->parsed())
            status = wp::run_export_mitsuba(export_mitsuba);
        else if (breakdown_app->parsed())
            status = wp::run_breakdown(breakdown);
        else
            status = wp::run_render(render);
    } catch (const wp::BuildError& e) {
        std::cerr << e.log() << "\nwavepath: error: " << e.what() << "\n";
    } catch (const cl::Error& e) {
        std::cerr << "wavepath: error: " << wp::describe_cl_error(e) << "\n";
    } catch (const std::bad_alloc&) {
        // An allocation without a name of its own (the film has one: commands.cpp).
        std::cerr << "wavepath: error: out of host memory\n";
    } catch (const std::exception& e) {
        std::cerr << "wavepath: error: " << e.what() << "\n";
    }
    return finish_stdout(status);
}
