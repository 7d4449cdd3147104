// The halt conditions of `wavepath render` besides --spp: a time budget
// (--time) and a target error (--target-error), alone and with --spp, where
// the first condition met ends the render (app/render_loop.hpp).
#include <catch2/catch.hpp>

#include <chrono>
#include <regex>
#include <string>

#include "app/cli_run.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "support/render_helpers.hpp"

using namespace wp::test::cli;
namespace fs = std::filesystem;

namespace {

struct TimedRun {
    Run run;
    double wall_seconds = 0.0;
};

TimedRun timed_wavepath(const std::string& arguments, const Scratch& s) {
    const auto start = std::chrono::steady_clock::now();
    TimedRun timed{wavepath(arguments, s), 0.0};
    timed.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return timed;
}

// The spp and render seconds of the summary line on stdout.
struct Summary {
    long spp = -1;
    double seconds = -1.0;
};

Summary summary(const Run& run, const std::string& size) {
    std::smatch match;
    Summary s;
    if (std::regex_search(run.out, match, std::regex(size + ", ([0-9]+) spp, ([0-9.]+) s, "))) {
        s.spp = std::stol(match[1]);
        s.seconds = std::stod(match[2]);
    }
    return s;
}

std::string metadata_spp(const fs::path& image_path) {
    for (const auto& [key, value] : wp::read_image(image_path).metadata)
        if (key == "wavepath.samples_per_pixel")
            return value;
    return "";
}

// The relMSE estimate from the even and odd half images of a film of `spp`
// samples per pixel in every pixel.
double estimate_from_halves(const wp::Film& film, std::uint32_t spp) {
    return wp::rel_mse_from_halves(film.half_mean(0), film.half_mean(1), spp - spp / 2, spp / 2);
}

} // namespace

TEST_CASE("cli: --time stops within one call of the budget and reports the spp reached") {
    Scratch s;
    // Calls of some 50 ms, long against the scheduler's jitter.
    const std::string render = "render " + kHexroom + " --width 160 --height 120 --quiet --out '" +
                               (s.dir / "out.exr").string() + "'";
    // Start-up (scene, kernels from the cache, film, one call, the write),
    // and one call's time, measured here on the same machine.
    const TimedRun startup = timed_wavepath(render + " --spp 1", s);
    REQUIRE(startup.run.exit_code == 0);
    const TimedRun sixteen = timed_wavepath(render + " --spp 16", s);
    REQUIRE(sixteen.run.exit_code == 0);
    const Summary calls = summary(sixteen.run, "160x120");
    REQUIRE(calls.spp == 16);
    const double measured_call = calls.seconds / 16.0; // one sample per call

    const double budget = 2.0;
    const TimedRun timed = timed_wavepath(render + " --time 2", s);
    INFO("stderr: " << timed.run.err << "\none call: " << measured_call << " s, start-up "
                    << startup.wall_seconds << " s, wall " << timed.wall_seconds << " s");
    REQUIRE(timed.run.exit_code == 0);
    std::smatch match;
    REQUIRE(std::regex_search(timed.run.err, match,
                              std::regex("time budget of 2 s reached: ([0-9]+) spp in "
                                         "([0-9.]+) s")));
    const long spp = std::stol(match[1]);
    const double seconds = std::stod(match[2]);
    REQUIRE(spp > 0);
    // One call's time: as measured, or as in this run where the machine was
    // busier.
    const double call = std::max(measured_call, seconds / static_cast<double>(spp));
    // The loop stops when the next call, predicted from the last ones, would
    // pass the budget: within one call of it on either side; two, for the
    // other jobs on a shared machine that make one call slower than the last.
    CHECK(seconds >= budget - 2.0 * call);
    CHECK(seconds <= budget + 2.0 * call);
    CHECK(timed.wall_seconds >= budget - 2.0 * call);
    CHECK(timed.wall_seconds <= budget + 2.0 * call + startup.wall_seconds);
    // The spp reached is the summary's and the image's.
    CHECK(spp > 8);
    CHECK(summary(timed.run, "160x120").spp == spp);
    CHECK(metadata_spp(s.dir / "out.exr") == std::to_string(spp));
}

TEST_CASE("cli: with --spp and --time the first condition met ends the render") {
    Scratch s;
    const std::string render = "render " + kHexroom + " --width 24 --height 16 --quiet --out '" +
                               (s.dir / "out.exr").string() + "'";
    // The spp bound first: long before a minute.
    const TimedRun few = timed_wavepath(render + " --spp 3 --time 60", s);
    INFO("stderr: " << few.run.err);
    REQUIRE(few.run.exit_code == 0);
    CHECK(summary(few.run, "24x16").spp == 3);
    CHECK(few.wall_seconds < 60.0);
    CHECK(few.run.err.find("time budget") == std::string::npos);
    // The time budget first.
    const TimedRun many = timed_wavepath(render + " --spp 1000000 --time 1", s);
    INFO("stderr: " << many.run.err);
    REQUIRE(many.run.exit_code == 0);
    CHECK(many.run.err.find("time budget of 1 s reached") != std::string::npos);
    const long spp = summary(many.run, "24x16").spp;
    CHECK(spp > 0);
    CHECK(spp < 1000000);
    CHECK(metadata_spp(s.dir / "out.exr") == std::to_string(spp));
}

TEST_CASE("cli: --target-error stops at the first estimate below the target") {
    Scratch s;
    const double target = 0.05;
    const Run run = wavepath("render " + kHexroom + " --width 32 --height 24 --quiet " +
                                 "--target-error 0.05 --out '" + (s.dir / "out.exr").string() + "'",
                             s);
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    std::smatch match;
    REQUIRE(std::regex_search(run.err, match,
                              std::regex("target error 0.05 reached: estimated relMSE ([0-9.e+-]+) "
                                         "at ([0-9]+) spp \\(([0-9.e+-]+) at ([0-9]+) spp\\)")));
    const double reported = std::stod(match[1]);
    const auto spp = static_cast<std::uint32_t>(std::stoul(match[2]));
    const double reported_before = std::stod(match[3]);
    const auto spp_before = static_cast<std::uint32_t>(std::stoul(match[4]));
    REQUIRE(spp >= 3);
    REQUIRE(spp_before < spp);
    CHECK(summary(run, "32x24").spp == spp);
    CHECK(metadata_spp(s.dir / "out.exr") == std::to_string(spp));

    // The same render in this process (same device, seed and one sample per
    // call, so the same film bit for bit), with the estimate recomputed from
    // its half images: below the target at the spp reached, above it at the
    // estimate before (the previous call's end).
    const wp::Scene scene = wp::test::hexroom(32, 24);
    wp::WavefrontIntegrator integrator(wp::test::device(), scene, wp::IntegratorOptions{});
    wp::Film film(32, 24);
    double at_spp = 0.0, at_spp_before = 0.0;
    for (std::uint32_t done = 0; done < spp; ++done) {
        integrator.render(done, 1, film);
        if (done + 1 == spp_before)
            at_spp_before = estimate_from_halves(film, spp_before);
    }
    at_spp = estimate_from_halves(film, spp);
    CHECK(at_spp < target);
    CHECK(at_spp == Approx(reported).epsilon(1e-3)); // printed to 4 digits
    CHECK(at_spp_before >= target);
    CHECK(at_spp_before == Approx(reported_before).epsilon(1e-3));
    // The estimate is made after every call, so spp_before is the previous
    // call's end (a call may render more than one sample per pixel when the
    // machine is slow: the render loop sizes calls by time, so spp - 1 need
    // not have been estimated at all).
}

TEST_CASE("cli: a target error not reached within --spp is said so") {
    Scratch s;
    const Run run = wavepath("render " + kHexroom + " --width 16 --height 12 --quiet --spp 4 " +
                                 "--target-error 1e-9 --out '" + (s.dir / "out.exr").string() + "'",
                             s);
    INFO("stderr: " << run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(summary(run, "16x12").spp == 4);
    CHECK(run.err.find("the target error 1e-09 was not reached within 4 spp: estimated relMSE ") !=
          std::string::npos);
}

TEST_CASE("cli: bad --time, --target-error and --preview values are one-line errors") {
    Scratch s;
    const fs::path out = s.dir / "never.exr";
    const auto [option, value] = GENERATE(table<std::string, std::string>({
        {"--time", "-1"},
        {"--time", "0"},
        {"--time", "nan"},
        {"--time", "inf"},
        {"--time", "soon"},
        {"--target-error", "-0.1"},
        {"--target-error", "nan"},
        {"--target-error", "0"},
        {"--preview", "70000"},
        {"--preview", "-1"},
    }));
    const Run run = wavepath("render " + kHexroom + " --width 8 --height 8 " + option + " " +
                                 value + " --out '" + out.string() + "'",
                             s);
    check_one_line_error(run, option);
    CHECK(!fs::exists(out));
}
