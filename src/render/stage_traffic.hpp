// How many bytes of global memory each stage moves per item: the figure the
// profile divides by a stage's time to say how far it is from its memory
// bound (docs/profiling.md, "Speed of light").
//
// The table (stage_traffic.cpp) lists, for every stage, the path buffers of
// kernels/wp_shared.h its kernel names and whether it reads or writes them.
// An item is counted as touching one element of each, once: the path that
// touches the most (a diffuse hit that queues a shadow ray and survives, for
// shade), so the bytes are an upper bound and the GB/s derived from them an
// upper bound of what the stage really moves. Not counted: the scene buffers
// (a few KiB that stay in cache on every bounce), and the atomics on
// `counters` (one cache line). tests/render/test_stage_traffic.cpp checks the
// table against the kernel sources, so a stage that starts touching another
// buffer fails a test until the table says so.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "render/profiler.hpp"

namespace wp {

enum class Access { Read = 1, Write = 2, ReadWrite = 3 };

struct BufferAccess {
    std::string_view buffer; // a name of WP_PATH_BUFFERS
    Access access;
};

// What the stage's kernel touches per item (empty for Stage::Transfer).
std::span<const BufferAccess> stage_buffer_accesses(Stage stage);

// Bytes of one element of a path buffer, from its type in WP_PATH_BUFFERS
// (0 for a name not in the list).
std::uint64_t path_buffer_element_bytes(std::string_view buffer);

// Bytes read plus bytes written per item (a read-write element counts twice).
std::uint64_t stage_bytes_per_item(Stage stage);

} // namespace wp
