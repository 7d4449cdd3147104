// Convergence reports: the hexroom's error against its stored reference falls
// at the Monte Carlo rate, the half-image error estimate agrees with the true
// error, and the CSV and SVG outputs parse.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "report/convergence.hpp"
#include "report/svg_plot.hpp"
#include "scene/load.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

using namespace wp;

namespace {

const std::string kHexroom = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";
// 32x32, 65536 spp, seed 1000003 (docs/convergence.md says how it was made).
const std::string kReference = std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/hexroom-32-ref.exr";

Scene hexroom(int size) {
    Scene scene = load_scene(kHexroom);
    scene.camera.width = size;
    scene.camera.height = size;
    return scene;
}

ConvergenceRun converge(const Scene& scene, const Image* reference, std::uint32_t max_spp,
                        std::uint32_t seed, IntegratorOptions options = {}) {
    options.seed = seed;
    WavefrontIntegrator integrator(test::device(), scene, options);
    Film film(scene.camera.width, scene.camera.height);
    ConvergenceSettings settings;
    settings.max_spp = max_spp;
    return run_convergence(integrator, film, reference, settings);
}

// Minimal XML well-formedness check: balanced, properly nested tags, quoted
// attributes, one root. Returns an empty string or what is wrong.
std::string xml_problem(const std::string& text) {
    std::vector<std::string> stack;
    int roots = 0;
    std::size_t i = 0;
    while ((i = text.find('<', i)) != std::string::npos) {
        const std::size_t end = text.find('>', i);
        if (end == std::string::npos)
            return "unterminated tag at " + std::to_string(i);
        const std::string tag = text.substr(i + 1, end - i - 1);
        i = end + 1;
        if (tag.empty())
            return "empty tag";
        if (tag[0] == '?' || tag[0] == '!')
            continue;
        std::size_t quotes = 0;
        for (char c : tag)
            quotes += c == '"';
        if (quotes % 2 != 0)
            return "unbalanced quotes in <" + tag + ">";
        if (tag[0] == '/') {
            if (stack.empty() || stack.back() != tag.substr(1))
                return "mismatched </" + tag.substr(1) + ">";
            stack.pop_back();
            continue;
        }
        const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
        if (stack.empty())
            ++roots;
        if (tag.back() != '/')
            stack.push_back(name);
    }
    if (!stack.empty())
        return "unclosed <" + stack.back() + ">";
    if (roots != 1)
        return std::to_string(roots) + " root elements";
    return "";
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1))
        ++n;
    return n;
}

} // namespace

// At 32x32 a handful of pixels hold most of the squared error: those the
// light's edges cross (each sample is 0 or 100 there) and those that see the
// light in the mirror. One image's MSE then varies by about 25 % between
// seeds, so the checks below pool several independent runs: disjoint sample
// ranges of one seed, each a full progressive run from its own first sample.

TEST_CASE("converge: the hexroom's RMSE against its reference falls with slope -1/2 from 4 to "
          "256 spp",
          "[convergence]") {
    const Image reference = read_image(kReference);
    const Scene scene = hexroom(32);
    IntegratorOptions options;
    options.seed = 7;
    // The rate of independent samples. Stratified ones (the default Sobol
    // sampler) converge faster where the light's edges cross pixels: -0.61
    // measured here (docs/convergence.md, "Samplers").
    options.sampler = Sampler::Independent;
    WavefrontIntegrator integrator(test::device(), scene, options);
    constexpr int kRuns = 4;
    std::vector<double> spp, mse_sum;
    for (int r = 0; r < kRuns; ++r) {
        Film film(32, 32);
        ConvergenceSettings settings;
        settings.max_spp = 256;
        settings.first_sample = 256u * static_cast<std::uint32_t>(r);
        settings.warm_up = r == 0;
        const ConvergenceRun run = run_convergence(integrator, film, &reference, settings);
        REQUIRE(run.checkpoints.size() == 9); // 1, 2, 4, ..., 256
        for (std::size_t i = 0; i < run.checkpoints.size(); ++i) {
            const Checkpoint& c = run.checkpoints[i];
            CHECK(c.against_reference);
            if (i > 0) // render times grow and exclude the kernel build
                CHECK(c.seconds > run.checkpoints[i - 1].seconds);
            if (r == 0) {
                spp.push_back(c.spp);
                mse_sum.push_back(0.0);
            }
            mse_sum[i] += c.mse;
        }
        INFO("run " << r << " alone: slope "
                    << log_log_slope(
                           spp,
                           [&] {
                               std::vector<double> rmse;
                               for (const Checkpoint& c : run.checkpoints)
                                   rmse.push_back(c.rmse);
                               return rmse;
                           }(),
                           4.0, 256.0));
        CHECK(true);
    }
    std::vector<double> rmse;
    for (std::size_t i = 0; i < spp.size(); ++i) {
        rmse.push_back(std::sqrt(mse_sum[i] / kRuns));
        INFO(spp[i] << " spp: RMSE " << rmse.back());
        CHECK(true);
    }
    const double slope = log_log_slope(spp, rmse, 4.0, 256.0);
    INFO("least-squares slope of log RMSE against log spp, 4 to 256 spp: " << slope);
    CHECK(slope > -0.6);
    CHECK(slope < -0.4);
}

TEST_CASE("converge: the half-image MSE estimate is within a factor 1.5 of the true MSE at 64 spp",
          "[convergence]") {
    const Image reference = read_image(kReference);
    const Scene scene = hexroom(32);
    IntegratorOptions options;
    options.seed = 11;
    // The half-image estimate assumes independent samples. With the Sobol
    // sampler each half is less evenly spread than the whole, so the estimate
    // overstates the error (6.4x measured here: conservative).
    options.sampler = Sampler::Independent;
    WavefrontIntegrator integrator(test::device(), scene, options);
    constexpr std::uint32_t kRuns = 16, kSpp = 64;
    double mse = 0.0, mse_halves = 0.0, rel_mse = 0.0, rel_mse_halves = 0.0;
    for (std::uint32_t r = 0; r < kRuns; ++r) {
        Film film(32, 32);
        integrator.render(r * kSpp, kSpp, film);
        const Checkpoint c = measure_checkpoint(film, kSpp, 1.0, &reference, r * kSpp);
        mse += c.mse / kRuns;
        mse_halves += c.mse_halves / kRuns;
        rel_mse += c.rel_mse / kRuns;
        rel_mse_halves += c.rel_mse_halves / kRuns;
    }
    const double ratio = mse_halves / mse;
    INFO("true MSE " << mse << ", half-image estimate " << mse_halves << ", ratio " << ratio);
    CHECK(ratio > 1.0 / 1.5);
    CHECK(ratio < 1.5);
    // relMSE's denominator needs the unknown reference: its estimate is a
    // plug-in (see rel_mse_from_halves), held to a looser bound.
    const double rel_ratio = rel_mse_halves / rel_mse;
    INFO("relMSE: true " << rel_mse << ", estimate " << rel_mse_halves << ", ratio " << rel_ratio);
    CHECK(rel_ratio > 0.4);
    CHECK(rel_ratio < 2.5);
}

TEST_CASE("converge: without a reference the error comes from the half images", "[convergence]") {
    const ConvergenceRun run = converge(hexroom(8), nullptr, 16, 3);
    REQUIRE(run.checkpoints.size() == 5);
    CHECK(std::isnan(run.checkpoints[0].mse)); // 1 spp: no odd half
    for (std::size_t i = 1; i < run.checkpoints.size(); ++i) {
        const Checkpoint& c = run.checkpoints[i];
        CHECK_FALSE(c.against_reference);
        CHECK(c.mse == c.mse_halves);
        CHECK(c.rmse == Approx(std::sqrt(c.mse)));
        CHECK(c.efficiency == Approx(1.0 / (c.mse * c.seconds)));
    }
}

TEST_CASE("converge: a time limit stops the run", "[convergence]") {
    Scene scene = hexroom(16);
    WavefrontIntegrator integrator(test::device(), scene, {});
    Film film(16, 16);
    ConvergenceSettings settings;
    settings.max_spp = 0;
    settings.max_seconds = 0.05;
    const ConvergenceRun run = run_convergence(integrator, film, nullptr, settings);
    REQUIRE_FALSE(run.checkpoints.empty());
    CHECK(run.checkpoints.back().seconds < 1.0); // a loaded machine may overshoot a little
    CHECK(film.min_samples() == run.checkpoints.back().spp);
    CHECK_THROWS(run_convergence(integrator, film, nullptr, ConvergenceSettings{0, 0.0, false}));
}

TEST_CASE("converge: checkpoint schedule, slope fit and time to a target error", "[convergence]") {
    CHECK(checkpoint_schedule(1) == std::vector<std::uint32_t>{1});
    CHECK(checkpoint_schedule(8) == std::vector<std::uint32_t>{1, 2, 4, 8});
    CHECK(checkpoint_schedule(12) == std::vector<std::uint32_t>{1, 2, 4, 8, 12});

    const std::vector<double> x{1, 2, 4, 8, 16}, y{8, 4, 2, 1, 0.5};
    CHECK(log_log_slope(x, y) == Approx(-1.0));
    CHECK(log_log_slope(x, {1, 2, 4, 8, 16}, 2.0, 8.0) == Approx(1.0));
    CHECK(std::isnan(log_log_slope({1}, {1})));

    std::vector<Checkpoint> checkpoints(3);
    checkpoints[0].seconds = 1.0;
    checkpoints[0].rel_mse = 0.4;
    checkpoints[1].seconds = 4.0;
    checkpoints[1].rel_mse = 0.1;
    checkpoints[2].seconds = 16.0;
    checkpoints[2].rel_mse = 0.025;
    CHECK(time_to_rel_mse(checkpoints, 0.05) == Approx(8.0)); // halfway in log-log
    CHECK(time_to_rel_mse(checkpoints, 0.4) == Approx(1.0));
    CHECK(std::isnan(time_to_rel_mse(checkpoints, 0.01)));
}

TEST_CASE("converge: the CSV round-trips and the SVG plot is well-formed XML", "[convergence]") {
    const test::TempDir dir;
    const ConvergenceRun run = converge(hexroom(8), nullptr, 8, 5);
    write_convergence_csv(dir / "run.csv", run);

    std::istringstream in(test::read_text(dir / "run.csv"));
    std::string header;
    std::getline(in, header);
    CHECK(header.rfind("estimator,width,height,spp,seconds,", 0) == 0);
    int lines = 0;
    for (std::string line; std::getline(in, line); ++lines)
        CHECK(count(line, ",") == count(header, ","));
    CHECK(lines == 4);

    const ConvergenceRun back = read_convergence_csv(dir / "run.csv");
    CHECK(back.estimator == "cosine+nee+area");
    CHECK(back.width == 8);
    REQUIRE(back.checkpoints.size() == run.checkpoints.size());
    for (std::size_t i = 0; i < run.checkpoints.size(); ++i) {
        CHECK(back.checkpoints[i].spp == run.checkpoints[i].spp);
        CHECK(back.checkpoints[i].seconds == Approx(run.checkpoints[i].seconds).epsilon(1e-8));
        CHECK(std::isnan(back.checkpoints[i].mse) == std::isnan(run.checkpoints[i].mse));
        if (!std::isnan(run.checkpoints[i].mse))
            CHECK(back.checkpoints[i].mse == Approx(run.checkpoints[i].mse).epsilon(1e-8));
    }

    // Two runs in one plot: two data polylines and the ideal slope line.
    ConvergenceRun other = back;
    other.estimator = "other";
    const std::string svg = render_svg(convergence_plot({run, other}, "hexroom <8x8> & test"));
    INFO(svg.substr(0, 400));
    CHECK(xml_problem(svg).empty());
    CHECK(xml_problem("<svg><g></svg></g>") != ""); // the checker itself catches nesting errors
    CHECK(count(svg, "<polyline") == 3);
    CHECK(count(svg, "ideal: RMSE ~ time^-1/2") == 1);
    CHECK(count(svg, "&lt;8x8&gt; &amp; test") == 1); // the title is escaped
    CHECK(count(svg, "render time in seconds") == 1);
    write_svg(dir / "plot.svg", convergence_plot({run}, "one run"));
    const std::string svg_text = test::read_text(dir / "plot.svg");
    CHECK(xml_problem(svg_text).empty());
    CHECK(count(svg_text, "<polyline") == 2);

    test::write_text(dir / "bad.csv", "estimator,nonsense\n");
    CHECK_THROWS_WITH(read_convergence_csv(dir / "bad.csv"),
                      Catch::Contains("not a convergence CSV"));
    CHECK_THROWS_WITH(read_convergence_csv(dir / "missing.csv"),
                      "cannot open '" + (dir / "missing.csv").string() +
                          "': No such file or directory");
}

TEST_CASE("svg plot: ticks, labels and skipped points", "[convergence]") {
    LogLogPlot plot;
    plot.x_label = "x";
    plot.y_label = "y";
    PlotSeries s;
    s.label = "data";
    s.x = {0.01, 0.1, 1, 10, -1};
    s.y = {100, 10, 1, 0.1, 5}; // the last point (x < 0) is skipped
    plot.series.push_back(s);
    const std::string svg = render_svg(plot);
    CHECK(xml_problem(svg).empty());
    CHECK(count(svg, "<circle") == 4);
    for (const char* tick : {">0.01<", ">0.1<", ">1<", ">10<", ">100<"})
        CHECK(count(svg, tick) >= 1);
    PlotSeries empty;
    empty.x = {-1};
    empty.y = {1};
    CHECK_THROWS(render_svg(LogLogPlot{"", "", "", 100, 100, {empty}}));
    PlotSeries uneven;
    uneven.x = {1, 2};
    uneven.y = {1};
    CHECK_THROWS(render_svg(LogLogPlot{"", "", "", 100, 100, {uneven}}));
}
