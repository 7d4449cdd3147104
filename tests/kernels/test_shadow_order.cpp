// The shadow queue's sort by origin (kernels/shadow_order.h): the launches
// shadow_order_count, shadow_order_scan and shadow_order_scatter against a
// host reference of the key (a double-precision Morton code of the origin's
// cell in the root's box) and of the counting sort: every queued slot once in
// shadow_order, keys in ascending order, each slot's ray copied to its place,
// nothing written past the queue;
// queues of odd lengths, one ray, none, and origins outside the box.
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

constexpr cl_uint kPool = 300;
constexpr cl_uint kSentinel = 0xdeadbeefu;
constexpr cl_uint kCells = 1u << WP_SHADOW_ORDER_AXIS_BITS;
const std::string kOptions = "-D WP_USE_BVH=1";

// A root whose children 0 and 2 span (-2, -1, 0) .. (6, 3, 8) together;
// children 1 and 3 are empty, with boxes that would widen it if read.
WpBvhNode root_node() {
    WpBvhNode n{};
    const float lower[4][3] = {{-2, -1, 0}, {-50, -50, -50}, {1, 0, 2}, {-50, -50, -50}};
    const float upper[4][3] = {{2, 3, 4}, {50, 50, 50}, {6, 1, 8}, {50, 50, 50}};
    for (int i = 0; i < 4; ++i) {
        n.lower_x[i] = lower[i][0];
        n.lower_y[i] = lower[i][1];
        n.lower_z[i] = lower[i][2];
        n.upper_x[i] = upper[i][0];
        n.upper_y[i] = upper[i][1];
        n.upper_z[i] = upper[i][2];
        n.child[i] = 0;
        n.count[i] = i % 2 == 0 ? 1u : WP_BVH_EMPTY;
    }
    return n;
}

// The key from its description: the cell along each axis of the box
// (-2, -1, 0) .. (6, 3, 8), clamped, its bits interleaved x, y, z from bit 0.
cl_uint reference_key(const cl_float4& origin) {
    const double low[3] = {-2, -1, 0}, high[3] = {6, 3, 8};
    cl_uint key = 0;
    for (int axis = 0; axis < 3; ++axis) {
        double at = (origin.s[axis] - low[axis]) / (high[axis] - low[axis]) * kCells;
        cl_uint cell = at <= 0.0 ? 0u : std::min(cl_uint(at), kCells - 1u);
        for (cl_uint bit = 0; bit < WP_SHADOW_ORDER_AXIS_BITS; ++bit)
            key |= ((cell >> bit) & 1u) << (3u * bit + cl_uint(axis));
    }
    return key;
}

// Origins of every slot: most inside the box, some outside it (clamped to
// the edge cells, two far beyond its corners), none on a cell boundary where float and double could
// round apart (a cell is 0.5 x 0.25 x 0.5 wide: coordinates on a 1/64 grid,
// shifted by 1/128).
std::vector<cl_float4> slot_origins() {
    std::mt19937 rng(35);
    std::uniform_int_distribution<int> step(-64, 8 * 64 + 64);
    std::vector<cl_float4> origins(kPool);
    for (cl_float4& o : origins) {
        const float scale[3] = {1.0f, 0.5f, 1.0f}, low[3] = {-2, -1, 0};
        for (int axis = 0; axis < 3; ++axis)
            o.s[axis] = low[axis] + scale[axis] * (float(step(rng)) + 0.5f) / 64.0f;
        o.s[3] = 0.0f;
    }
    origins[0] = float4(-10, -10, -10); // below the box: the first corner cell
    origins[1] = float4(100, 100, 100); // above it: the last
    return origins;
}

std::vector<cl_uint> shuffled_slots(cl_uint seed) {
    std::vector<cl_uint> slots(kPool);
    for (cl_uint i = 0; i < kPool; ++i)
        slots[i] = i;
    std::shuffle(slots.begin(), slots.end(), std::mt19937(seed));
    return slots;
}

// Sorts the first `length` entries of `queue` as the integrator does: the
// counts zeroed, then the three launches.
struct Sorted {
    std::vector<cl_uint> order;               // shadow_order
    std::vector<cl_float4> origin, direction; // the rays' copies in that order
};

// Each slot's direction: (slot, -slot, 2 slot, length slot + 0.5), to tell
// the copies apart.
cl_float4 slot_direction(cl_uint slot) {
    const float f = float(slot);
    return float4(f, -f, 2.0f * f, f + 0.5f);
}

Sorted run_sort(const std::vector<cl_float4>& origins, const std::vector<cl_uint>& queue,
                cl_uint length) {
    WpFrame frame{};
    frame.pool_size = kPool;
    WpLaunch arguments{};
    arguments.count = length;
    DeviceBuffers buffers = stage_buffers(kPool, 1);
    buffers.bvh_nodes = upload(std::vector<WpBvhNode>{root_node()});
    buffers.shadow_origin = upload(origins);
    std::vector<cl_float4> directions;
    for (cl_uint slot = 0; slot < kPool; ++slot)
        directions.push_back(slot_direction(slot));
    buffers.shadow_direction = upload(directions);
    buffers.shadow_queue = upload(queue);
    buffers.shadow_key_counts = upload(std::vector<cl_uint>(WP_SHADOW_KEY_COUNT, 0u));
    buffers.shadow_order = upload(std::vector<cl_uint>(kPool, kSentinel));
    run_stage("shadow_order_count", frame, arguments, buffers, length, kOptions);
    run_stage("shadow_order_scan", frame, arguments, buffers, 1, kOptions);
    run_stage("shadow_order_scatter", frame, arguments, buffers, length, kOptions);
    return {download<cl_uint>(buffers.shadow_order, kPool),
            download<cl_float4>(buffers.shadow_order_origin, kPool),
            download<cl_float4>(buffers.shadow_order_direction, kPool)};
}

void check_sorted(const std::vector<cl_float4>& origins, const std::vector<cl_uint>& queued,
                  const Sorted& sorted) {
    const std::vector<cl_uint>& order = sorted.order;
    const std::size_t n = queued.size();
    std::vector<cl_uint> got(order.begin(), order.begin() + std::ptrdiff_t(n));
    std::vector<cl_uint> want = queued;
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    CHECK(got == want); // every queued slot exactly once
    for (std::size_t i = 1; i < n; ++i) {
        INFO("place " << i);
        REQUIRE(order[i] < kPool);
        REQUIRE(order[i - 1] < kPool);
        CHECK(reference_key(origins[order[i - 1]]) <= reference_key(origins[order[i]]));
    }
    for (std::size_t i = 0; i < n; ++i) { // each place holds its slot's ray
        INFO("place " << i);
        REQUIRE(order[i] < kPool);
        CHECK(std::memcmp(&sorted.origin[i], &origins[order[i]], sizeof(cl_float4)) == 0);
        const cl_float4 d = slot_direction(order[i]);
        CHECK(std::memcmp(&sorted.direction[i], &d, sizeof(cl_float4)) == 0);
    }
    for (std::size_t i = n; i < kPool; ++i)
        CHECK(order[i] == kSentinel); // nothing past the queue
}

} // namespace

TEST_CASE("shadow order: every queued slot once, keys ascending (Morton codes of the origins' "
          "cells); odd lengths, one ray, none, origins outside the box",
          "[cl][shadow-order]") {
    const std::vector<cl_float4> origins = slot_origins();
    std::vector<cl_uint> keys;
    for (const cl_float4& o : origins)
        keys.push_back(reference_key(o));
    std::sort(keys.begin(), keys.end());
    // The origins reach the corner cells and many between.
    CHECK(keys.front() == 0u);
    CHECK(keys.back() == WP_SHADOW_KEY_COUNT - 1u);
    CHECK(std::unique(keys.begin(), keys.end()) - keys.begin() > 100);
    for (cl_uint length : {0u, 1u, 63u, 64u, 65u, 251u, kPool}) {
        INFO(length << " rays");
        std::vector<cl_uint> queue = shuffled_slots(length);
        const std::vector<cl_uint> queued(queue.begin(), queue.begin() + length);
        std::fill(queue.begin() + length, queue.end(), kSentinel); // past the end: not read
        check_sorted(origins, queued, run_sort(origins, queue, length));
    }
}
