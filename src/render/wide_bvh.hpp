// The builder's binary tree (scene/bvh.hpp) as the device's eight-wide nodes
// (WpBvhNode, kernels/wp_shared.h).
//
// The collapse is greedy by surface area, as in Embree and Wald et al. 2008
// ("Getting rid of packets"): a wide node starts with its binary node's two
// children and, while it has room, replaces the inner child of largest
// surface area by that child's two children. The probability that a random
// ray visits a box goes with its area, so the largest boxes are the ones
// worth testing together with their siblings rather than as a node of their
// own. Leaves stay as the builder made them.
#pragma once

#include <cstdint>
#include <vector>

#include "render/device_array.hpp"
#include "scene/bvh.hpp"
#include "wp_shared.h"

namespace wp {

// A node of the binary tree as the device needs it: `offset` is an inner
// node's second child (its first follows it) or a leaf's first primitive.
struct BinaryNode {
    Bounds3f bounds;
    wp_uint offset = 0;
    wp_uint count = 0; // 0 for an inner node
};

// Appends the tree `binary` (depth first, binary[0] the root) to `out` as
// wide nodes, the root first at out.size() on entry; inner children point
// into `out`, leaves keep their primitive ranges. Returns the most stack
// entries the kernels' walks (kernels/bvh.h, bvh_any_hit.h) can hold on
// the deepest path: each node pushes the children it hits, and the walk
// takes one of them next.
std::uint32_t write_wide_nodes(const std::vector<BinaryNode>& binary, DeviceArray<WpBvhNode>& out);

} // namespace wp
