// Shade's sort by material (kernels/shade_sort.cl): the two launches
// shade_sort_count and shade_sort against a host reference of the counting
// sort: the counts per key, every queued slot exactly once in shade_order,
// grouped by key in key order with each key's range where the prefix sums
// say, nothing written past the queue; with kinds no ray hit, a queue of one
// key and an empty queue.
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <array>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

constexpr cl_uint kPool = 300;
constexpr cl_uint kSentinel = 0xdeadbeefu;
constexpr std::size_t kKeys = WP_SHADE_KEY_COUNT;

// A scene of materials only as the sort sees them: triangle i has material
// kTriangleMaterials[i], sphere j kSphereMaterials[j]; material m is of kind
// kKinds[m]. Two materials share a kind (the key is the kind, not the
// material); roughconductor, thindielectric, roughdielectric and
// roughplastic are no one's (empty keys).
constexpr std::array<cl_uint, 7> kKinds = {
    WP_MATERIAL_DIFFUSE, WP_MATERIAL_MIRROR,  WP_MATERIAL_EMITTER,   WP_MATERIAL_CONDUCTOR,
    WP_MATERIAL_DIFFUSE, WP_MATERIAL_PLASTIC, WP_MATERIAL_DIELECTRIC};
constexpr std::array<cl_uint, 5> kTriangleMaterials = {0, 1, 2, 3, 4};
constexpr std::array<cl_uint, 2> kSphereMaterials = {6, 1};

struct SortScene {
    std::vector<WpTriangle> triangles;
    std::vector<WpSphere> spheres;
    std::vector<WpMaterial> materials;
};

SortScene sort_scene() {
    SortScene s;
    for (cl_uint kind : kKinds) {
        WpMaterial m{};
        m.kind = kind;
        s.materials.push_back(m);
    }
    for (cl_uint material : kTriangleMaterials) {
        WpTriangle t{};
        wp_set_triangle_material(&t, material);
        s.triangles.push_back(t);
    }
    for (cl_uint material : kSphereMaterials) {
        WpSphere sphere{};
        sphere.material = material;
        s.spheres.push_back(sphere);
    }
    return s;
}

// The key of a hit, from the description in wp_shared.h.
cl_uint reference_key(const SortScene& s, cl_uint primitive) {
    if (primitive == WP_NO_HIT)
        return WP_SHADE_KEY_MISS;
    const cl_uint material = primitive < s.triangles.size()
                                 ? wp_triangle_material(&s.triangles[primitive])
                                 : s.spheres[primitive - s.triangles.size()].material;
    return s.materials[material].kind;
}

struct SortResult {
    std::vector<cl_uint> counts; // shade_key_counts: counts, then cursors
    std::vector<cl_uint> order;  // shade_order, all kPool entries
};

// Sorts the first `length` entries of ray queue `queue` (of the two in
// ray_queues) with the slots' hits `hits`, as the integrator launches it:
// over the whole pool, surplus work-items included.
SortResult run_sort(const SortScene& s, const std::vector<cl_uint>& ray_queues, cl_uint queue,
                    cl_uint length, const std::vector<cl_uint>& hits) {
    WpFrame frame{};
    frame.pool_size = kPool;
    frame.triangle_count = static_cast<cl_uint>(s.triangles.size());
    frame.sphere_count = static_cast<cl_uint>(s.spheres.size());
    WpLaunch arguments{};
    arguments.ray_queue = queue;
    DeviceBuffers buffers = stage_buffers(kPool, 1);
    buffers.triangles = upload(s.triangles);
    buffers.spheres = upload(s.spheres);
    buffers.materials = upload(s.materials);
    buffers.ray_queues = upload(ray_queues);
    buffers.hit_primitive = upload(hits);
    std::vector<cl_uint> counters(WP_COUNTER_COUNT, 0u);
    counters[queue] = length;
    buffers.counters = upload(counters);
    buffers.shade_key_counts = upload(std::vector<cl_uint>(2 * kKeys, 0u));
    buffers.shade_order = upload(std::vector<cl_uint>(kPool, kSentinel));
    run_stage("shade_sort_count", frame, arguments, buffers, kPool);
    run_stage("shade_sort", frame, arguments, buffers, kPool);
    return {download<cl_uint>(buffers.shade_key_counts, 2 * kKeys),
            download<cl_uint>(buffers.shade_order, kPool)};
}

// Every check of the sort against the host's counting sort of
// queue[0, length).
void check_sorted(const SortScene& s, const std::vector<cl_uint>& queued,
                  const std::vector<cl_uint>& hits, const SortResult& result) {
    std::vector<cl_uint> count(kKeys, 0u);
    for (cl_uint slot : queued)
        ++count[reference_key(s, hits[slot])];
    for (std::size_t k = 0; k < kKeys; ++k) {
        INFO("key " << k);
        CHECK(result.counts[k] == count[k]);
        CHECK(result.counts[kKeys + k] == count[k]); // every place reserved once
    }
    const std::size_t n = queued.size();
    // Each queued slot exactly once ...
    std::vector<cl_uint> got(result.order.begin(), result.order.begin() + std::ptrdiff_t(n));
    std::vector<cl_uint> want = queued;
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    CHECK(got == want);
    // ... in key k's range [start_k, start_k + count_k), the prefix sums.
    std::size_t start = 0;
    for (std::size_t k = 0; k < kKeys; ++k) {
        for (std::size_t i = start; i < start + count[k]; ++i) {
            INFO("key " << k << ", place " << i);
            REQUIRE(result.order[i] < kPool);
            CHECK(reference_key(s, hits[result.order[i]]) == k);
        }
        start += count[k];
    }
    // Nothing past the queue's end.
    for (std::size_t i = n; i < kPool; ++i)
        CHECK(result.order[i] == kSentinel);
}

// A deterministic shuffle of 0 .. kPool - 1 (a linear congruential
// generator's Fisher-Yates), and hits that mix every present key.
std::vector<cl_uint> shuffled_slots(cl_uint seed) {
    std::vector<cl_uint> slots(kPool);
    for (cl_uint i = 0; i < kPool; ++i)
        slots[i] = i;
    std::uint32_t state = seed;
    for (cl_uint i = kPool - 1; i > 0; --i) {
        state = state * 1664525u + 1013904223u;
        std::swap(slots[i], slots[(state >> 8) % (i + 1)]);
    }
    return slots;
}

} // namespace

TEST_CASE("shade sort: counts per material kind, every queued slot once, grouped by kind in "
          "key order; empty kinds and surplus work-items",
          "[cl][shade-sort]") {
    const SortScene s = sort_scene();
    const cl_uint primitives =
        static_cast<cl_uint>(s.triangles.size() + s.spheres.size()); // and a miss
    std::vector<cl_uint> hits(kPool);
    for (cl_uint slot = 0; slot < kPool; ++slot)
        hits[slot] = (slot * 7u + 3u) % (primitives + 1u) == primitives
                         ? WP_NO_HIT
                         : (slot * 7u + 3u) % (primitives + 1u);
    for (cl_uint queue : {0u, 1u})
        for (cl_uint length : {1u, 63u, 64u, 250u, kPool}) {
            INFO("ray queue " << queue << ", " << length << " rays");
            const std::vector<cl_uint> slots = shuffled_slots(length + queue);
            // Queue `queue` holds the first `length` shuffled slots; the other
            // queue holds garbage the sort must not read.
            std::vector<cl_uint> ray_queues(2 * kPool, kSentinel);
            std::copy(slots.begin(), slots.begin() + length,
                      ray_queues.begin() + std::ptrdiff_t(queue * kPool));
            const std::vector<cl_uint> queued(slots.begin(), slots.begin() + length);
            check_sorted(s, queued, hits, run_sort(s, ray_queues, queue, length, hits));
        }
    // The present keys: diffuse (two materials), mirror (a triangle and a
    // sphere), emitter, conductor, dielectric (a sphere) and the miss; plastic
    // (material 5) is no primitive's.
    std::vector<cl_uint> present;
    for (cl_uint primitive = 0; primitive < primitives; ++primitive)
        present.push_back(reference_key(s, primitive));
    CHECK(std::count(present.begin(), present.end(), WP_MATERIAL_PLASTIC) == 0);
    CHECK(std::count(present.begin(), present.end(), WP_MATERIAL_DIFFUSE) == 2);
    CHECK(std::count(present.begin(), present.end(), WP_MATERIAL_MIRROR) == 2);
}

TEST_CASE("shade sort: a queue of one key, and an empty queue, which writes nothing",
          "[cl][shade-sort]") {
    const SortScene s = sort_scene();
    const std::vector<cl_uint> slots = shuffled_slots(7);
    std::vector<cl_uint> ray_queues(2 * kPool, kSentinel);
    std::copy(slots.begin(), slots.end(), ray_queues.begin());
    {
        INFO("every ray missed");
        const std::vector<cl_uint> misses(kPool, WP_NO_HIT);
        const SortResult result = run_sort(s, ray_queues, 0, 200, misses);
        check_sorted(s, std::vector<cl_uint>(slots.begin(), slots.begin() + 200), misses, result);
        CHECK(result.counts[WP_SHADE_KEY_MISS] == 200);
    }
    {
        INFO("an empty queue");
        const std::vector<cl_uint> hits(kPool, 0u);
        const SortResult result = run_sort(s, ray_queues, 0, 0, hits);
        CHECK(result.counts == std::vector<cl_uint>(2 * kKeys, 0u));
        CHECK(result.order == std::vector<cl_uint>(kPool, kSentinel));
    }
}
