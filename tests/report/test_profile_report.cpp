// The profile's reports: the JSON file and the Chrome trace hold what they
// claim, one trace event per kernel launch.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "report/profile_report.hpp"
#include "support/render_helpers.hpp"
#include "support/temp_dir.hpp"

using namespace wp;

TEST_CASE("profile: the JSON and the trace parse, one trace event per launch") {
    const test::ProfiledRender r = test::profiled_render(test::hexroom(8, 8), 2, true);
    ProfileContext context;
    context.device = test::profiling_device().info.name;
    context.scene = "hexroom";
    context.width = context.height = 8;
    context.spp = 2;
    context.build_options = "-D X=1";
    const test::TempDir dir;
    write_profile_json(dir / "p.json", r.profiler, r.stats, context);
    r.profiler.write_trace(dir / "t.json", context.device);

    nlohmann::json profile = nlohmann::json::parse(test::read_text(dir / "p.json"));
    CHECK(profile["device"] == context.device);
    CHECK(profile["spp"] == 2);
    CHECK(profile["build_options"] == "-D X=1");
    double stage_sum = 0.0;
    std::uint64_t launches = 0;
    for (const auto& stage : profile["stages"]) {
        stage_sum += stage["device_seconds"].get<double>();
        launches += stage["launches"].get<std::uint64_t>();
    }
    CHECK(stage_sum <= profile["wall_seconds"].get<double>());
    CHECK(profile["rays"]["camera"] == 8 * 8 * 2);

    nlohmann::json trace = nlohmann::json::parse(test::read_text(dir / "t.json"));
    std::uint64_t complete_events = 0;
    for (const auto& event : trace["traceEvents"])
        if (event["ph"] == "X") {
            ++complete_events;
            CHECK(event["dur"].get<double>() >= 0.0);
        }
    CHECK(complete_events == launches);
    CHECK(complete_events == r.profiler.records().size());
}

TEST_CASE("profile: each stage's GB/s is its items times bytes per item over its time") {
    const test::ProfiledRender r = test::profiled_render(test::hexroom(8, 8), 2, true);
    ProfileContext context;
    context.memory_bandwidth = 10e9; // a round figure, so the fraction is checkable
    const nlohmann::json profile = profile_json(r.profiler, r.stats, context);
    CHECK(profile["copy_bandwidth_gigabytes_per_second"].get<double>() == Approx(10.0));
    int checked = 0;
    for (const auto& stage : profile["stages"]) {
        if (stage["stage"] == "transfers") {
            CHECK_FALSE(stage.contains("gigabytes_per_second"));
            continue;
        }
        INFO(stage.dump());
        const double seconds = stage["device_seconds"].get<double>();
        REQUIRE(seconds > 0.0);
        const double bytes = static_cast<double>(stage["items"].get<std::uint64_t>()) *
                             static_cast<double>(stage["bytes_per_item"].get<std::uint64_t>());
        CHECK(stage["bytes_per_item"].get<std::uint64_t>() > 0);
        CHECK(stage["gigabytes_per_second"].get<double>() == Approx(bytes / seconds * 1e-9));
        CHECK(stage["fraction_of_copy_bandwidth"].get<double>() == Approx(bytes / seconds / 10e9));
        ++checked;
    }
    CHECK(checked == 5);
    // The table prints the same figures, with the bandwidth line below it.
    const std::string table = profile_table(r.profiler, r.stats, context);
    CHECK(table.find("GB/s") != std::string::npos);
    CHECK(table.find("a copy kernel moves 10.00 GB/s") != std::string::npos);
}
