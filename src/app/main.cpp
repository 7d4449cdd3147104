// wavepath: a wavefront Monte Carlo path tracer on OpenCL.
//
// This file only parses the command line and turns every failure into one
// line on stderr and a non-zero exit; the subcommands live in commands.cpp,
// bench.cpp, converge.cpp, compare.cpp and info.cpp.
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "cl/device.hpp"
#include "cl/error.hpp"
#include "cl/program.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"

int main(int argc, char** argv) {
    CLI::App app{"wavepath: a wavefront Monte Carlo path tracer on OpenCL"};
    app.require_subcommand(1);

    app.add_subcommand("devices", "List every OpenCL platform and device");

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

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) { // --help
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "wavepath: error: " << e.what() << " (see wavepath --help)\n";
        return 2;
    }

    try {
        if (app.got_subcommand("devices"))
            return wp::run_devices();
        if (app.got_subcommand("bench"))
            return wp::run_bench(bench);
        if (converge_app->parsed())
            return wp::run_converge(converge);
        if (compare_app->parsed())
            return wp::run_compare(compare);
        if (info_app->parsed())
            return wp::run_info(info);
        return wp::run_render(render);
    } catch (const wp::BuildError& e) {
        std::cerr << e.log() << "\nwavepath: error: " << e.what() << "\n";
    } catch (const cl::Error& e) {
        std::cerr << "wavepath: error: " << wp::describe_cl_error(e) << "\n";
    } catch (const std::exception& e) {
        std::cerr << "wavepath: error: " << e.what() << "\n";
    }
    return 1;
}
