// The hierarchy builder: every primitive in exactly one leaf, every node's box
// holding its children's and its primitives' boxes, the depth within the
// device's stack, the SAH cost it reports equal to one computed from the
// finished tree, and a tree that does not depend on the number of threads
// (byte for byte, on random boxes and the bunny).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "scene/bvh.hpp"
#include "scene/mesh.hpp"

using namespace wp;

namespace {

// Random boxes: clusters of small ones, a few long thin ones, and many with
// the same centroid (which no plane can separate).
std::vector<Bounds3f> random_boxes(std::size_t n, unsigned seed) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Bounds3f> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        Bounds3f b;
        glm::vec3 c(unit(generator), unit(generator), unit(generator));
        if (i % 97 == 0)
            c = glm::vec3(0.5f); // a pile of equal centroids
        c *= 100.0f;
        glm::vec3 half(unit(generator), unit(generator), unit(generator));
        if (i % 31 == 0)
            half.x *= 50.0f; // long and thin
        b.extend(c - half);
        b.extend(c + half);
        boxes.push_back(b);
    }
    return boxes;
}

// Checks the tree below `node` and returns the primitives it holds.
void check_subtree(const Bvh& bvh, std::uint32_t node, const std::vector<Bounds3f>& boxes,
                   std::vector<int>& seen, std::uint32_t depth, std::uint32_t& deepest) {
    REQUIRE(node < bvh.nodes.size());
    const BvhNode& n = bvh.nodes[node];
    deepest = std::max(deepest, depth);
    if (n.is_leaf()) {
        REQUIRE(n.first_primitive + n.primitive_count <= bvh.primitives.size());
        for (std::uint32_t k = 0; k < n.primitive_count; ++k) {
            const std::uint32_t p = bvh.primitives[n.first_primitive + k];
            REQUIRE(p < boxes.size());
            seen[p] += 1;
            CHECK(n.bounds.contains(boxes[p]));
        }
        return;
    }
    const std::uint32_t first = node + 1, second = n.second_child;
    REQUIRE(second > first);
    CHECK(n.bounds.contains(bvh.nodes[first].bounds));
    CHECK(n.bounds.contains(bvh.nodes[second].bounds));
    check_subtree(bvh, first, boxes, seen, depth + 1, deepest);
    check_subtree(bvh, second, boxes, seen, depth + 1, deepest);
}

} // namespace

TEST_CASE("bvh: every primitive exactly once, boxes nested, depth and SAH cost as reported",
          "[bvh]") {
    for (std::size_t n : {1u, 2u, 5u, 100u, 20000u}) {
        INFO(n << " boxes");
        const std::vector<Bounds3f> boxes = random_boxes(n, static_cast<unsigned>(n));
        const Bvh bvh = build_bvh(boxes);
        std::vector<int> seen(n, 0);
        std::uint32_t deepest = 0;
        check_subtree(bvh, 0, boxes, seen, 0, deepest);
        CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
        CHECK(bvh.stats.nodes == bvh.nodes.size());
        CHECK(bvh.stats.depth == deepest);
        CHECK(bvh.stats.depth <= BvhBuildOptions{}.max_depth);
        CHECK(bvh.stats.leaves * 2 - 1 == bvh.stats.nodes); // a full binary tree
        CHECK(bvh.stats.sah_cost == Approx(bvh_sah_cost(bvh)).epsilon(1e-12));
        // Better than one leaf of everything, from a few primitives on.
        if (n >= 100)
            CHECK(bvh.stats.sah_cost < 0.1 * static_cast<double>(n));
    }
}

namespace {

// The same flat arrays, byte for byte, and the same statistics.
void check_same_tree(const Bvh& a, const Bvh& b) {
    static_assert(sizeof(BvhNode) == 36, "no padding: the nodes compare byte for byte");
    REQUIRE(a.nodes.size() == b.nodes.size());
    CHECK(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)) == 0);
    CHECK(a.primitives == b.primitives);
    CHECK(a.stats.leaves == b.stats.leaves);
    CHECK(a.stats.depth == b.stats.depth);
    CHECK(a.stats.largest_leaf == b.stats.largest_leaf);
    CHECK(a.stats.sah_cost == b.stats.sah_cost);
}

// The boxes of the bunny's triangles in float, as the device's hierarchy has them.
std::vector<Bounds3f> bunny_boxes() {
    const TriangleMesh mesh = load_mesh(WAVEPATH_SOURCE_DIR "/scenes/models/stanford-bunny.obj");
    std::vector<Bounds3f> boxes;
    for (const auto& triangle : mesh.triangles) {
        Bounds3f b;
        for (std::uint32_t v : triangle)
            b.extend(glm::vec3(mesh.positions[v]));
        boxes.push_back(b);
    }
    return boxes;
}

} // namespace

// Subtrees go to other threads from 256 primitives on, so that many are
// handed over and appended; 1, 2 and 4 threads give the same arrays.
TEST_CASE("bvh: the tree does not depend on the number of threads", "[bvh]") {
    const std::vector<std::pair<const char*, std::vector<Bounds3f>>> scenes = {
        {"random boxes", random_boxes(200000, 3)}, {"the bunny", bunny_boxes()}};
    for (const auto& [name, boxes] : scenes) {
        INFO(name << ", " << boxes.size() << " boxes");
        REQUIRE(boxes.size() > 60000);
        BvhBuildOptions options; // the device hierarchy's
        options.max_leaf_size = 8;
        options.traversal_cost = 2.0;
        options.parallel_subtree = 256;
        options.threads = 1;
        const Bvh serial = build_bvh(boxes, options);
        for (std::uint32_t threads : {2u, 4u}) {
            INFO(threads << " threads");
            options.threads = threads;
            check_same_tree(serial, build_bvh(boxes, options));
        }
        // The default hand-over size, on as many threads as the machine has.
        options.threads = 0;
        options.parallel_subtree = BvhBuildOptions{}.parallel_subtree;
        check_same_tree(serial, build_bvh(boxes, options));
    }
}

TEST_CASE("bvh: WAVEPATH_BVH_THREADS sets the threads, and a bad value is one clear error",
          "[bvh]") {
    const std::vector<Bounds3f> boxes = random_boxes(100000, 5);
    BvhBuildOptions one;
    one.threads = 1;
    const Bvh serial = build_bvh(boxes, one);
    const char* saved = std::getenv("WAVEPATH_BVH_THREADS");
    const std::string restore = saved ? saved : "";
    ::setenv("WAVEPATH_BVH_THREADS", "2", 1);
    check_same_tree(serial, build_bvh(boxes));
    ::setenv("WAVEPATH_BVH_THREADS", "two", 1);
    CHECK_THROWS_WITH(build_bvh(boxes), "WAVEPATH_BVH_THREADS must be a whole number from 1 to "
                                        "1024, got 'two'");
    CHECK_NOTHROW(build_bvh(boxes, one)); // the options' count comes first
    if (saved)
        ::setenv("WAVEPATH_BVH_THREADS", restore.c_str(), 1);
    else
        ::unsetenv("WAVEPATH_BVH_THREADS");
}

TEST_CASE("bvh: a depth limit turns deeper nodes into leaves", "[bvh]") {
    const std::vector<Bounds3f> boxes = random_boxes(5000, 9);
    BvhBuildOptions shallow;
    shallow.max_depth = 5;
    const Bvh bvh = build_bvh(boxes, shallow);
    std::vector<int> seen(boxes.size(), 0);
    std::uint32_t deepest = 0;
    check_subtree(bvh, 0, boxes, seen, 0, deepest);
    CHECK(deepest <= 5);
    CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    CHECK(build_bvh({}).nodes.empty());
}

// A golden hash: the builder's memory-saving partition (bvh.cpp) must give
// the very nodes, in the same order, that std::stable_partition gave, since
// the golden images depend on the hierarchy. The hashes are main's builder's
// at commit d9c3793 on these boxes (FNV-1a over every node's bounds, second
// child, first primitive and count, then the primitive order).
TEST_CASE("bvh: the same tree as before the partition that buffers the smaller side", "[bvh]") {
    const std::vector<Bounds3f> boxes = random_boxes(200000, 3);
    for (const auto& [leaf, hash] :
         {std::pair<std::uint32_t, std::uint64_t>{4, 0x7a559a55eb9b846aull},
          {8, 0x0aa01d0dc0a25f15ull}}) {
        BvhBuildOptions options;
        options.max_leaf_size = leaf;
        options.traversal_cost = leaf == 8 ? 2.0 : 1.0; // 8: the device hierarchy's options
        const Bvh bvh = build_bvh(boxes, options);
        std::uint64_t h = 14695981039346656037ull;
        auto mix = [&h](const void* p, std::size_t n) {
            const auto* c = static_cast<const unsigned char*>(p);
            for (std::size_t i = 0; i < n; ++i) {
                h ^= c[i];
                h *= 1099511628211ull;
            }
        };
        for (const BvhNode& n : bvh.nodes) {
            mix(&n.bounds.lower, sizeof n.bounds.lower);
            mix(&n.bounds.upper, sizeof n.bounds.upper);
            mix(&n.second_child, 4);
            mix(&n.first_primitive, 4);
            mix(&n.primitive_count, 4);
        }
        mix(bvh.primitives.data(), 4 * bvh.primitives.size());
        INFO("leaves of at most " << leaf);
        CHECK(h == hash);
    }
}
