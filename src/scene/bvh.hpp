// A bounding volume hierarchy over boxes, built with the surface area
// heuristic.
//
// The builder knows nothing of triangles or spheres: it takes one
// axis-aligned box per primitive (in float, exactly the boxes the device
// will test, so that they contain the primitives the device intersects) and
// returns a binary tree in depth-first order. Each inner node's first child
// follows it; its second child is at `second_child`. Leaves list a range of
// `primitives`, the primitive numbers reordered so every leaf's are
// contiguous.
//
// Splits are chosen by binned SAH (Wald 2007): at every node the primitives'
// centroids are sorted into kBins bins along each axis, and the split plane
// between two bins that minimises
//     cost = traversal + (area(left) n_left + area(right) n_right) / area(node)
// wins, unless a leaf is cheaper. Subtrees of many primitives are built on
// their own threads, each into a node array of its own that its parent
// appends in the tree's order: the result, node for node, does not depend on
// the number of threads or on their timing.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace wp {

struct Bounds3f {
    glm::vec3 lower{std::numeric_limits<float>::infinity()};
    glm::vec3 upper{-std::numeric_limits<float>::infinity()};

    bool empty() const { return lower.x > upper.x; }
    void extend(const Bounds3f& b) { // inline: the builder's inner loops call it
        lower = glm::min(lower, b.lower);
        upper = glm::max(upper, b.upper);
    }
    void extend(const glm::vec3& p) {
        lower = glm::min(lower, p);
        upper = glm::max(upper, p);
    }
    glm::vec3 centroid() const { return 0.5f * (lower + upper); }
    double surface_area() const; // 0 for an empty box
    bool contains(const Bounds3f& b) const;
};

struct BvhNode {
    Bounds3f bounds;
    std::uint32_t second_child = 0;    // inner nodes
    std::uint32_t first_primitive = 0; // leaves: into Bvh::primitives
    std::uint32_t primitive_count = 0; // 0 for an inner node
    bool is_leaf() const { return primitive_count > 0; }
};

struct BvhBuildOptions {
    std::uint32_t max_leaf_size = 4; // leaves are split until this small ...
    double traversal_cost = 1.0;     // ... or until a leaf is cheaper by SAH
    double intersection_cost = 1.0;  // per primitive in a leaf
    std::uint32_t max_depth = 48;    // deeper nodes become leaves (the device stack)
    // 0: WAVEPATH_BVH_THREADS if set (1 forces a serial build), else
    // std::thread::hardware_concurrency(); at most 16.
    std::uint32_t threads = 0;
    // Subtrees of at least this many primitives on either side of a split
    // may go to another thread (smaller ones cost more to hand over than to
    // build); tests lower it to hand over many.
    std::uint32_t parallel_subtree = 1u << 15;
};

struct BvhStats {
    std::uint32_t nodes = 0;
    std::uint32_t leaves = 0;
    std::uint32_t depth = 0;        // of the deepest leaf (the root has depth 0)
    std::uint32_t largest_leaf = 0; // primitives
    double sah_cost = 0.0;          // expected cost of a random ray, by the SAH
    double build_seconds = 0.0;
};

struct Bvh {
    std::vector<BvhNode> nodes; // depth first; nodes[0] is the root
    std::vector<std::uint32_t> primitives;
    BvhStats stats;
};

// The hierarchy over `boxes` (primitive i has box i). Empty input gives an
// empty hierarchy (no nodes). The boxes are taken by value and freed once the
// builder has its own copy: a caller done with them moves them in, so that a
// big scene's build does not hold both.
Bvh build_bvh(std::vector<Bounds3f> boxes, const BvhBuildOptions& options = {});

// SAH cost of a finished hierarchy (what BvhStats::sah_cost reports).
double bvh_sah_cost(const Bvh& bvh, const BvhBuildOptions& options = {});

} // namespace wp
