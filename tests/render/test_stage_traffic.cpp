// The profile's bytes per item (render/stage_traffic.hpp) against the kernel
// sources: a stage's table lists exactly the path buffers its kernel file
// names, read where the source reads them and written where it writes them.
#include <catch2/catch.hpp>

#include <regex>
#include <set>
#include <string>

#include "cl/program.hpp"
#include "render/stage_traffic.hpp"
#include "wp_shared.h"

using namespace wp;

namespace {

// The source without its comments, whose prose names buffers too.
std::string code_of(std::string_view file) {
    static const std::regex comments(R"(/\*[\s\S]*?\*/|//[^\n]*)");
    return std::regex_replace(std::string(kernel_file(file)), comments, " ");
}

// What the source does with `buffer`: read by an index that is not an
// assignment's target (or by `+=`), by a scalar load (wp_load_xyz, wp_load_w)
// or through a pointer to an element; written by an assignment, a queue push
// (one item's or a work-group's)
// or through a pointer to an element that is not const (per-component updates
// such as `sum[0] += add[0]`, which also read it).
int source_access(const std::string& code, const std::string& buffer) {
    const std::string index = "\\b" + buffer + R"(\s*\[[^\]]*\])";
    const std::string element = R"(\*\)\s*\(\s*)" + buffer + R"(\s*\+)";
    const bool through_pointer =
        std::regex_search(code, std::regex(R"(\(__global\s+\w+\s*)" + element));
    const bool read =
        std::regex_search(code, std::regex(index + R"((?!\s*=[^=]))")) ||
        std::regex_search(code,
                          std::regex(R"(wp_ray_queue\(\s*)" + buffer + R"(\b[^;]*?\)\s*\[)")) ||
        std::regex_search(code, std::regex(R"(\bwp_load_\w+\(\s*)" + buffer + "\\b")) ||
        std::regex_search(code, std::regex(R"(\(__global\s+const\s+\w+\s*)" + element)) ||
        through_pointer;
    const bool written =
        std::regex_search(code, std::regex(index + R"(\s*(\+=|=[^=]))")) ||
        std::regex_search(code, std::regex(R"(wp_(group_)?queue_push\(\s*(wp_ray_queue\(\s*)?)" +
                                           buffer + "\\b")) ||
        through_pointer;
    return (read ? 1 : 0) | (written ? 2 : 0);
}

} // namespace

TEST_CASE("stage traffic: each stage's table matches the buffers its kernel touches") {
    std::set<std::string> path_buffers;
#define WP_NAME(name, ...) path_buffers.insert(#name);
    WP_PATH_BUFFERS(WP_NAME)
#undef WP_NAME
    path_buffers.erase("counters");         // atomics on one cache line, not counted
    path_buffers.erase("shade_key_counts"); // the same, per key (shade_sort.cl)
    for (Stage stage : {Stage::Generate, Stage::Intersect, Stage::ShadeSort, Stage::Shade,
                        Stage::Shadow, Stage::Accumulate}) {
        const std::string file = std::string(stage_name(stage)) + ".cl";
        const std::string code = code_of(file);
        std::set<std::string> listed;
        for (const BufferAccess& a : stage_buffer_accesses(stage)) {
            INFO(file << ": " << a.buffer);
            CHECK(path_buffers.count(std::string(a.buffer)) == 1);
            CHECK(listed.insert(std::string(a.buffer)).second); // listed once
            CHECK(source_access(code, std::string(a.buffer)) == static_cast<int>(a.access));
        }
        for (const std::string& buffer : path_buffers) {
            INFO(file << " names " << buffer << ", which its table does not list");
            if (!listed.count(buffer))
                CHECK_FALSE(std::regex_search(code, std::regex("\\b" + buffer + "\\b")));
        }
    }
}

TEST_CASE("stage traffic: bytes per item add up the element sizes of the buffer list") {
    // Independent of the table's arithmetic: sizes from the host's own types.
    CHECK(path_buffer_element_bytes("ray_origin") == sizeof(cl_float4));
    CHECK(path_buffer_element_bytes("hit_t") == sizeof(cl_float));
    CHECK(path_buffer_element_bytes("no such buffer") == 0);
    // intersect: a queue entry, origin and direction in; hit distance and primitive out.
    CHECK(stage_bytes_per_item(Stage::Intersect) == 4 + 16 + 16 + 4 + 4);
    // accumulate: a queue entry, radiance, pixel, sample in; three film float4 read and written.
    CHECK(stage_bytes_per_item(Stage::Accumulate) == 4 + 16 + 4 + 4 + 3 * 2 * 16);
    CHECK(stage_bytes_per_item(Stage::Transfer) == 0);
    // shade: the AOV rows are listed (the source names them) but, written only
    // with --aov and only at a camera ray's hit, not counted per item.
    std::uint64_t shade = 0;
    int aov_rows = 0;
    for (const BufferAccess& a : stage_buffer_accesses(Stage::Shade)) {
        const bool aov = a.buffer.substr(0, 4) == "aov_";
        aov_rows += aov;
        if (!aov)
            shade += path_buffer_element_bytes(a.buffer) * (a.access == Access::ReadWrite ? 2 : 1);
    }
    CHECK(aov_rows == 3);
    CHECK(stage_bytes_per_item(Stage::Shade) == shade);
}
