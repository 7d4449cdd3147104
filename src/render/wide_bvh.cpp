#include "render/wide_bvh.hpp"

#include <algorithm>

namespace wp {

namespace {

// A binary tree within the depth cap fits the stack even left binary (see
// WideWriter::open), so the collapse never has to refuse one.
static_assert(WP_BVH_MAX_DEPTH + 1 <= WP_BVH_STACK_SIZE);

class WideWriter {
  public:
    WideWriter(const std::vector<BinaryNode>& binary, DeviceArray<WpBvhNode>& out)
        : binary_(binary), out_(out), height_(binary.size(), 0) {
        // Children follow their parents (depth first), so one backward pass
        // sees every child's height before its parent's.
        for (std::size_t n = binary.size(); n-- > 0;)
            if (binary[n].count == 0)
                height_[n] = 1 + std::max(height_[n + 1], height_[binary[n].offset]);
    }

    // `base`: the stack entries the walk holds when it visits this node (the
    // ancestors' waiting children).
    std::uint32_t write(std::uint32_t binary, std::uint32_t base) {
        std::uint32_t slots[WP_BVH_WIDTH];
        const int used = open(binary, base, slots);
        const std::size_t at = out_.size();
        out_.emplace_back();
        std::uint32_t deepest = 0;
        for (int i = 0; i < WP_BVH_WIDTH; ++i) {
            WpBvhNode& n = out_[at];
            if (i >= used) {
                n.lower_x[i] = n.lower_y[i] = n.lower_z[i] = 0.0f;
                n.upper_x[i] = n.upper_y[i] = n.upper_z[i] = 0.0f;
                n.child[i] = 0;
                n.count[i] = WP_BVH_EMPTY;
                continue;
            }
            const BinaryNode& c = binary_[slots[i]];
            n.lower_x[i] = c.bounds.lower.x;
            n.lower_y[i] = c.bounds.lower.y;
            n.lower_z[i] = c.bounds.lower.z;
            n.upper_x[i] = c.bounds.upper.x;
            n.upper_y[i] = c.bounds.upper.y;
            n.upper_z[i] = c.bounds.upper.z;
            n.count[i] = c.count;
            if (c.count > 0) {
                n.child[i] = c.offset;
            } else {
                const auto child = static_cast<wp_uint>(out_.size());
                deepest =
                    std::max(deepest, write(slots[i], base + static_cast<std::uint32_t>(used) - 1));
                out_[at].child[i] = child; // out_ may have moved
            }
        }
        // This node's entries, then the one taken next and its own on top.
        return std::max<std::uint32_t>(static_cast<std::uint32_t>(used),
                                       deepest > 0 ? used - 1 + deepest : 0);
    }

  private:
    // The children of the wide node for binary node `binary`, in tree order
    // (left to right, as the binary tree has them), into slots; returns how
    // many. A root that is a leaf is its own only child.
    //
    // The stack: a node of k children visited with `base` entries waiting
    // holds base + k, and its children are visited with base + k - 1. Below a
    // binary node of height h (inner levels) the binary tree itself needs at
    // most base + h + 1. So a child is opened only while base + k + h <=
    // WP_BVH_STACK_SIZE for every inner child of height h: then each child,
    // even left binary, fits, and by induction so does every path. At the
    // root (base 0, height at most WP_BVH_MAX_DEPTH) two children always
    // fit, so no tree is refused; only deep, lopsided paths get narrower
    // nodes.
    int open(std::uint32_t binary, std::uint32_t base, std::uint32_t* slots) const {
        if (binary_[binary].count > 0) {
            slots[0] = binary;
            return 1;
        }
        slots[0] = binary + 1;
        slots[1] = binary_[binary].offset;
        int used = 2;
        while (used < WP_BVH_WIDTH) {
            int widest = -1;
            double widest_area = -1.0;
            for (int i = 0; i < used; ++i) {
                const BinaryNode& c = binary_[slots[i]];
                if (c.count > 0)
                    continue;
                const double area = c.bounds.surface_area();
                if (area > widest_area) { // the first of equal areas: deterministic
                    widest = i;
                    widest_area = area;
                }
            }
            if (widest < 0)
                break; // every child is a leaf
            if (!fits_opened(slots, used, widest, base))
                break;
            const std::uint32_t opened = slots[widest];
            std::copy_backward(slots + widest + 1, slots + used, slots + used + 1);
            slots[widest] = opened + 1;
            slots[widest + 1] = binary_[opened].offset;
            ++used;
        }
        return used;
    }

    // Whether the node still fits the stack (open's rule) with slots[opened]
    // replaced by its two children.
    bool fits_opened(const std::uint32_t* slots, int used, int opened, std::uint32_t base) const {
        std::uint32_t tallest = 0; // inner children's heights, after the opening
        for (int i = 0; i < used; ++i) {
            const std::uint32_t n = slots[i];
            if (i == opened)
                tallest = std::max({tallest, height_[n + 1], height_[binary_[n].offset]});
            else
                tallest = std::max(tallest, height_[n]);
        }
        return base + static_cast<std::uint32_t>(used) + 1 + tallest <= WP_BVH_STACK_SIZE;
    }

    const std::vector<BinaryNode>& binary_;
    DeviceArray<WpBvhNode>& out_;
    std::vector<std::uint32_t> height_; // inner levels below each binary node; 0 for a leaf
};

} // namespace

std::uint32_t write_wide_nodes(const std::vector<BinaryNode>& binary, DeviceArray<WpBvhNode>& out) {
    return WideWriter(binary, out).write(0, 0);
}

} // namespace wp
