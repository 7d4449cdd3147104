// The binary tree collapsed into eight-wide nodes (render/wide_bvh.hpp), on
// the host: the nodes the device walks, checked against the scene's own
// primitives. Every primitive is reachable exactly once, every box holds what
// is below it, no node is wider than eight, a node has room left only when
// every child is a leaf (the greedy collapse opens inner children while it
// can) or the stack needs it narrow, and the stack bound the writer reports is what a walk that
// hits every box really pushes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "render/device_scene.hpp"
#include "render/wide_bvh.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

// Random loose triangles of many sizes, a strip of small ones, and spheres:
// leaves of both kinds and mixed leaves split by kind.
Scene random_scene(unsigned seed, int triangles, int spheres) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Scene scene;
    scene.camera = test::make_camera({0, 0, -20}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 8);
    const auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    for (int k = 0; k < triangles; ++k) {
        const glm::dvec3 c(20 * unit(generator) - 10, 20 * unit(generator) - 10,
                           20 * unit(generator) - 10);
        const double size = std::pow(10.0, 2.0 * unit(generator) - 2.0);
        auto corner = [&] {
            return c + size * glm::dvec3(unit(generator) - 0.5, unit(generator) - 0.5,
                                         unit(generator) - 0.5);
        };
        scene.triangles.push_back({{corner(), corner(), corner()}, white});
    }
    for (int k = 0; k < 300; ++k) {
        const double x = 0.01 * k;
        scene.triangles.push_back(
            {{glm::dvec3(x, 0, 0), glm::dvec3(x + 0.01, 0, 0), glm::dvec3(x, 0.01, 0)}, white});
    }
    for (int k = 0; k < spheres; ++k)
        scene.spheres.push_back({glm::dvec3(20 * unit(generator) - 10, 20 * unit(generator) - 10,
                                            20 * unit(generator) - 10),
                                 0.05 + unit(generator), white});
    return scene;
}

Bounds3f child_box(const WpBvhNode& n, int i) {
    Bounds3f b;
    b.lower = glm::vec3(n.lower_x[i], n.lower_y[i], n.lower_z[i]);
    b.upper = glm::vec3(n.upper_x[i], n.upper_y[i], n.upper_z[i]);
    return b;
}

struct Walk {
    std::vector<int> reached;      // per primitive, how many leaves hold it
    std::uint32_t most_pushed = 0; // the stack's high-water mark, every box hit
    std::uint32_t worst = 0;       // the most any order of visits can push
    std::uint32_t nodes_seen = 0;
    std::uint32_t narrowed = 0; // nodes with room and an inner child: kept narrow for the stack
};

// Depth first as the kernels walk, every child hit: push a node's children,
// take the top one next: the last child, or with first_child_first the first
// (pushed last). Checks each node on the way. Whatever the order, when a
// node is visited its ancestors' other children may all be waiting: the
// worst stack is the largest sum, over a path, of each ancestor's children
// less one, plus the node's own.
void walk(const DeviceArray<WpBvhNode>& nodes, std::uint32_t triangle_count, Walk& w,
          const std::vector<Bounds3f>& primitive_boxes, bool first_child_first) {
    struct Entry {
        std::uint32_t child, count;
        Bounds3f box;
        std::uint32_t waiting; // its ancestors' other children
    };
    std::vector<Entry> stack;
    Entry current{0, 0, {}, 0};
    bool root = true;
    for (;;) {
        if (current.count == 0) {
            REQUIRE(current.child < nodes.size());
            ++w.nodes_seen;
            const WpBvhNode& n = nodes[current.child];
            int used = 0, leaves = 0;
            const std::size_t below = stack.size();
            for (int i = 0; i < WP_BVH_WIDTH; ++i) {
                if (n.count[i] == WP_BVH_EMPTY) {
                    for (int j = i; j < WP_BVH_WIDTH; ++j) // the used children come first
                        REQUIRE(n.count[j] == WP_BVH_EMPTY);
                    break;
                }
                ++used;
                leaves += n.count[i] > 0;
                const Bounds3f box = child_box(n, i);
                if (!root)
                    REQUIRE(current.box.contains(box));
                stack.push_back({n.child[i], n.count[i], box, 0});
            }
            for (std::size_t k = below; k < stack.size(); ++k)
                stack[k].waiting = current.waiting + static_cast<std::uint32_t>(used) - 1;
            w.worst = std::max(w.worst, current.waiting + static_cast<std::uint32_t>(used));
            if (first_child_first)
                std::reverse(stack.begin() + static_cast<std::ptrdiff_t>(below), stack.end());
            REQUIRE(used <= WP_BVH_WIDTH);
            REQUIRE(used >= (root ? 1 : 2));
            if (used < WP_BVH_WIDTH && leaves < used)
                ++w.narrowed; // room left, yet an inner child not opened
            root = false;
            w.most_pushed = std::max(w.most_pushed, static_cast<std::uint32_t>(stack.size()));
        } else {
            REQUIRE(current.child + current.count <= w.reached.size());
            // A leaf is of one kind: all triangles or none.
            REQUIRE((current.child + current.count <= triangle_count ||
                     current.child >= triangle_count));
            for (std::uint32_t p = current.child; p < current.child + current.count; ++p) {
                ++w.reached[p];
                REQUIRE(current.box.contains(primitive_boxes[p]));
            }
        }
        if (stack.empty())
            break;
        current = stack.back();
        stack.pop_back();
    }
}

// The primitives' boxes of a binary tree made by hand: its leaves' boxes.
std::vector<Bounds3f> leaf_boxes(const std::vector<BinaryNode>& binary, std::uint32_t primitives) {
    std::vector<Bounds3f> boxes(primitives);
    for (const BinaryNode& b : binary)
        if (b.count > 0)
            boxes[b.offset] = b.bounds;
    return boxes;
}

// The walk of a tree made by hand, in both orders of visit; each must reach
// every primitive and node once.
std::vector<Walk> walk_both_orders(const DeviceArray<WpBvhNode>& nodes,
                                   const std::vector<BinaryNode>& binary,
                                   std::uint32_t primitives) {
    const std::vector<Bounds3f> boxes = leaf_boxes(binary, primitives);
    std::vector<Walk> walks;
    for (bool first_child_first : {false, true}) {
        Walk& w = walks.emplace_back();
        w.reached.assign(primitives, 0);
        walk(nodes, primitives, w, boxes, first_child_first);
        CHECK(std::all_of(w.reached.begin(), w.reached.end(), [](int r) { return r == 1; }));
        CHECK(w.nodes_seen == nodes.size());
    }
    return walks;
}

} // namespace

TEST_CASE("bvh collapse: eight-wide nodes reach every primitive once, boxes nest, full nodes",
          "[bvh]") {
    for (unsigned seed : {1u, 2u, 3u}) {
        for (int triangles : {1, 7, 200, 20000}) {
            CAPTURE(seed, triangles);
            const Scene scene = random_scene(seed, triangles, triangles / 10);
            const DeviceScene flat = flatten_scene(scene, true);
            REQUIRE(!flat.bvh_nodes.empty());
            const std::vector<Bounds3f> boxes = primitive_boxes(flat);
            for (bool first_child_first : {false, true}) {
                Walk w;
                w.reached.assign(flat.triangles.size() + flat.spheres.size(), 0);
                walk(flat.bvh_nodes, static_cast<std::uint32_t>(flat.triangles.size()), w, boxes,
                     first_child_first);
                CHECK(w.nodes_seen == flat.bvh_nodes.size()); // no node unreachable
                CHECK(
                    std::all_of(w.reached.begin(), w.reached.end(), [](int r) { return r == 1; }));
                CHECK(w.most_pushed <= w.worst);
                CHECK(w.worst <= WP_BVH_STACK_SIZE);
                CHECK(w.narrowed == 0); // these trees are far from the stack's limit
            }
        }
    }
}

TEST_CASE("bvh collapse: the widest inner child is opened first; the stack bound is the walk's",
          "[bvh]") {
    // A binary tree by hand, depth first: node 0 over a small inner node A
    // (a chain of leaves) and a large inner node B (a chain too). Leaves are
    // unit boxes along x; an inner node's box is its children's.
    std::vector<BinaryNode> binary;
    std::uint32_t next_primitive = 0;
    // A chain of `leaves` leaves at x0, x0 + step, ...: inner nodes whose first
    // child is a leaf and second the rest.
    auto chain = [&](auto& self, float x0, float step, int leaves) -> std::uint32_t {
        const auto at = static_cast<std::uint32_t>(binary.size());
        binary.emplace_back();
        if (leaves == 1) {
            binary[at].bounds.extend(glm::vec3(x0, 0, 0));
            binary[at].bounds.extend(glm::vec3(x0 + 1, 1, 1));
            binary[at].offset = next_primitive++;
            binary[at].count = 1;
            return at;
        }
        const std::uint32_t first = self(self, x0, step, 1);
        const std::uint32_t second = self(self, x0 + step, step, leaves - 1);
        binary[at].bounds = binary[first].bounds;
        binary[at].bounds.extend(binary[second].bounds);
        binary[at].offset = second;
        return at;
    };
    binary.emplace_back();                                      // the root
    const std::uint32_t small = chain(chain, 0.0f, 0.5f, 12);   // 6.5 long
    const std::uint32_t large = chain(chain, 100.0f, 4.0f, 12); // 45 long
    REQUIRE(small == 1);
    binary[0].bounds = binary[small].bounds;
    binary[0].bounds.extend(binary[large].bounds);
    binary[0].offset = large;

    DeviceArray<WpBvhNode> nodes;
    const std::uint32_t bound = write_wide_nodes(binary, nodes);
    // The root opens B (the larger) six times (B's chain stays the largest
    // inner child throughout): A, then six of B's leaves, then B's rest.
    const WpBvhNode& root = nodes[0];
    CHECK(root.count[0] == 0); // A, not opened
    CHECK(root.lower_x[0] == 0.0f);
    for (int i = 1; i < 7; ++i) {
        CHECK(root.count[i] == 1);
        CHECK(root.lower_x[i] == 100.0f + 4.0f * float(i - 1));
    }
    CHECK(root.count[7] == 0);
    CHECK(root.lower_x[7] == 124.0f);

    // The bound is the worst order's: A's rest (five leaves) walked while
    // the root's seven other children and A's seven leaves wait, 7 + 7 + 5 =
    // 19; the walk that takes the last child first holds at most 7 + 6 = 13.
    for (const Walk& w : walk_both_orders(nodes, binary, next_primitive)) {
        CHECK(w.most_pushed <= bound);
        CHECK(w.worst == bound);
    }
    CHECK(bound == 19);
}

TEST_CASE("bvh collapse: a lopsided tree is kept within the stack by narrower nodes", "[bvh]") {
    // A spine of `levels` inner nodes; beside each, a complete subtree of
    // eight unit-like leaves so large that the greedy collapse opens it before
    // the spine. Collapsed without regard to the stack, every wide node would
    // hold seven of those leaves and the spine's next node, so a walk down
    // the spine could leave 7 a level waiting: 7 x 16 = 112 entries, past
    // WP_BVH_STACK_SIZE.
    constexpr int levels = 16;
    std::vector<BinaryNode> binary;
    std::uint32_t next_primitive = 0;
    auto leaf = [&](glm::vec3 lower, glm::vec3 upper) {
        const auto at = static_cast<std::uint32_t>(binary.size());
        binary.emplace_back();
        binary[at].bounds.extend(lower);
        binary[at].bounds.extend(upper);
        binary[at].offset = next_primitive++;
        binary[at].count = 1;
        return at;
    };
    // Inner node over the children made by first() and second().
    auto inner = [&](auto first, auto second) {
        const auto at = static_cast<std::uint32_t>(binary.size());
        binary.emplace_back();
        const std::uint32_t a = first();
        const std::uint32_t b = second();
        REQUIRE(a == at + 1);
        binary[at].bounds = binary[a].bounds;
        binary[at].bounds.extend(binary[b].bounds);
        binary[at].offset = b;
        return at;
    };
    // Leaves first .. first + count - 1 of a side subtree of scale s: boxes of
    // side s at x = 2 s (j + 1).
    auto side = [&](auto& self, float s, int first, int count) -> std::uint32_t {
        if (count == 1)
            return leaf({2 * s * float(first + 1), 0, 0}, {2 * s * float(first + 1) + s, s, s});
        const int half = count / 2;
        return inner([&] { return self(self, s, first, half); },
                     [&] { return self(self, s, first + half, count - half); });
    };
    // The spine below level i: level i's side subtree (scale 10^(levels - i))
    // is larger than everything deeper (at most 17 x 10^(levels - i - 1) long).
    auto spine = [&](auto& self, int i) -> std::uint32_t {
        if (i == levels)
            return leaf({0, 0, 0}, {1, 1, 1});
        const float s = std::pow(10.0f, float(levels - i));
        return inner([&] { return side(side, s, 0, 8); }, [&] { return self(self, i + 1); });
    };
    REQUIRE(spine(spine, 0) == 0);

    DeviceArray<WpBvhNode> nodes;
    const std::uint32_t bound = write_wide_nodes(binary, nodes);
    CHECK(bound <= WP_BVH_STACK_SIZE);
    // At the top, where the stack has room, the collapse is the plain greedy
    // one: six of the side subtree's leaves, its last pair and the spine.
    const WpBvhNode& root = nodes[0];
    int root_leaves = 0;
    for (int i = 0; i < WP_BVH_WIDTH; ++i)
        root_leaves += root.count[i] != WP_BVH_EMPTY && root.count[i] > 0;
    CHECK(root.count[WP_BVH_WIDTH - 1] != WP_BVH_EMPTY); // full
    CHECK(root_leaves == 6);

    for (const Walk& w : walk_both_orders(nodes, binary, next_primitive)) {
        CHECK(w.worst == bound);
        CHECK(w.narrowed > 0); // deeper down the stack did bind
    }
}
