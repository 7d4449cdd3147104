#include "render/wide_bvh.hpp"

#include <algorithm>

namespace wp {

namespace {

class WideWriter {
  public:
    WideWriter(const std::vector<BinaryNode>& binary, DeviceArray<WpBvhNode>& out)
        : binary_(binary), out_(out) {}

    std::uint32_t write(std::uint32_t binary) {
        std::uint32_t slots[WP_BVH_WIDTH];
        const int used = open(binary, slots);
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
                deepest = std::max(deepest, write(slots[i]));
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
    int open(std::uint32_t binary, std::uint32_t* slots) const {
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
            const std::uint32_t opened = slots[widest];
            std::copy_backward(slots + widest + 1, slots + used, slots + used + 1);
            slots[widest] = opened + 1;
            slots[widest + 1] = binary_[opened].offset;
            ++used;
        }
        return used;
    }

    const std::vector<BinaryNode>& binary_;
    DeviceArray<WpBvhNode>& out_;
};

} // namespace

std::uint32_t write_wide_nodes(const std::vector<BinaryNode>& binary, DeviceArray<WpBvhNode>& out) {
    return WideWriter(binary, out).write(0);
}

} // namespace wp
