// The children's boxes of a four-wide node (WpBvhNode, kernels/wp_shared.h)
// in 8 bits a coordinate: what the node's layout comment describes, and the
// decode that the kernel runs (kernels/bvh.h), so that tests can check one
// against the other.
#pragma once

#include "scene/bvh.hpp"
#include "wp_shared.h"

namespace wp {

// Sets node's origin, exponents and the quantised bounds of children
// 0 .. count - 1 (count <= 4) from their float boxes; a child past count gets
// an empty box (its count field is the caller's: WP_BVH_EMPTY). Each child's
// decoded box contains its float box, whatever the boxes: flat, huge, or
// with infinite or NaN coordinates (such an axis decodes to NaN bounds, no
// limit to the kernel's slab test).
void quantise_child_boxes(const Bounds3f* boxes, int count, WpBvhNode& node);

// Child i's box as the kernel decodes it: origin + q * scale per bound, in
// float.
Bounds3f decoded_child_box(const WpBvhNode& node, int i);

} // namespace wp
