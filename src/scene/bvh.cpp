#include "scene/bvh.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <memory>
#include <thread>

#include <glm/common.hpp>

namespace wp {

double Bounds3f::surface_area() const {
    if (empty())
        return 0.0;
    const glm::dvec3 d = glm::dvec3(upper) - glm::dvec3(lower);
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

bool Bounds3f::contains(const Bounds3f& b) const {
    return b.empty() || (lower.x <= b.lower.x && lower.y <= b.lower.y && lower.z <= b.lower.z &&
                         upper.x >= b.upper.x && upper.y >= b.upper.y && upper.z >= b.upper.z);
}

namespace {

constexpr int kBins = 16;
// Subtrees of at least this many primitives are built on a thread of their own.
constexpr std::size_t kParallelSubtree = 1 << 15;

struct Primitive {
    Bounds3f bounds;
    glm::vec3 centroid;
    std::uint32_t index;
};

// The tree while it is built: children by pointer, so that subtrees built on
// different threads need no shared node array.
struct BuildNode {
    Bounds3f bounds;
    std::unique_ptr<BuildNode> children[2];
    std::uint32_t first = 0, count = 0; // leaves: a range of the primitive array
};

struct Split {
    int axis = -1;
    int bin = 0; // primitives in bins [0, bin] go left
    double cost = std::numeric_limits<double>::infinity();
};

class Builder {
  public:
    Builder(std::vector<Primitive>& primitives, const BvhBuildOptions& options)
        : primitives_(primitives), options_(options) {
        unsigned threads = options.threads ? options.threads : std::thread::hardware_concurrency();
        spare_threads_ = static_cast<int>(std::max(1u, threads)) - 1;
    }

    std::unique_ptr<BuildNode> build(std::size_t begin, std::size_t end, std::uint32_t depth) {
        auto node = std::make_unique<BuildNode>();
        Bounds3f centroids;
        for (std::size_t i = begin; i < end; ++i) {
            node->bounds.extend(primitives_[i].bounds);
            centroids.extend(primitives_[i].centroid);
        }
        const std::size_t count = end - begin;
        auto make_leaf = [&] {
            node->first = static_cast<std::uint32_t>(begin);
            node->count = static_cast<std::uint32_t>(count);
            return std::move(node);
        };
        if (count <= options_.max_leaf_size || depth >= options_.max_depth)
            return make_leaf();

        const Split split = best_split(begin, end, node->bounds, centroids);
        const double leaf_cost = options_.intersection_cost * static_cast<double>(count);
        // A leaf when no plane separates the centroids, or when a leaf is
        // cheaper and small enough to stay fast in the worst case.
        if (split.axis < 0 || (split.cost >= leaf_cost && count <= 4 * options_.max_leaf_size))
            return make_leaf();

        std::size_t middle = partition(begin, end, centroids, split);
        if (middle == begin || middle == end) { // centroids too close for the bins
            middle = begin + count / 2;
            const int axis = split.axis;
            std::nth_element(primitives_.begin() + static_cast<std::ptrdiff_t>(begin),
                             primitives_.begin() + static_cast<std::ptrdiff_t>(middle),
                             primitives_.begin() + static_cast<std::ptrdiff_t>(end),
                             [axis](const Primitive& a, const Primitive& b) {
                                 return a.centroid[axis] < b.centroid[axis] ||
                                        (a.centroid[axis] == b.centroid[axis] && a.index < b.index);
                             });
        }

        // The larger child on another thread, if one is free.
        std::future<std::unique_ptr<BuildNode>> left_async;
        if (std::min(middle - begin, end - middle) >= kParallelSubtree && take_thread())
            left_async = std::async(std::launch::async, [this, begin, middle, depth] {
                auto subtree = build(begin, middle, depth + 1);
                ++spare_threads_;
                return subtree;
            });
        node->children[1] = build(middle, end, depth + 1);
        node->children[0] = left_async.valid() ? left_async.get() : build(begin, middle, depth + 1);
        return node;
    }

  private:
    bool take_thread() {
        int spare = spare_threads_.load();
        while (spare > 0)
            if (spare_threads_.compare_exchange_weak(spare, spare - 1))
                return true;
        return false;
    }

    static int bin_of(const glm::vec3& centroid, const Bounds3f& centroids, int axis) {
        const float extent = centroids.upper[axis] - centroids.lower[axis];
        const float x = (centroid[axis] - centroids.lower[axis]) / extent;
        return std::clamp(static_cast<int>(x * static_cast<float>(kBins)), 0, kBins - 1);
    }

    // One pass over the primitives bins them along all three axes (the
    // primitives are read once, not once an axis: binning is most of the
    // build's time).
    Split best_split(std::size_t begin, std::size_t end, const Bounds3f& node_bounds,
                     const Bounds3f& centroids) const {
        Split best;
        const double node_area = node_bounds.surface_area();
        bool splittable[3];
        for (int axis = 0; axis < 3; ++axis)
            splittable[axis] = centroids.upper[axis] > centroids.lower[axis];
        if (!splittable[0] && !splittable[1] && !splittable[2])
            return best;
        std::array<std::array<Bounds3f, kBins>, 3> bins;
        std::array<std::array<std::size_t, kBins>, 3> counts{};
        for (std::size_t i = begin; i < end; ++i) {
            const Primitive& p = primitives_[i];
            for (int axis = 0; axis < 3; ++axis) {
                if (!splittable[axis])
                    continue; // a zero extent has no bins
                const int b = bin_of(p.centroid, centroids, axis);
                bins[axis][b].extend(p.bounds);
                ++counts[axis][b];
            }
        }
        for (int axis = 0; axis < 3; ++axis) {
            if (!splittable[axis])
                continue;
            // Sweep from the right: the cost of everything right of each plane.
            std::array<double, kBins> right_cost{};
            Bounds3f right;
            std::size_t right_count = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.extend(bins[axis][b]);
                right_count += counts[axis][b];
                right_cost[b] = right.surface_area() * static_cast<double>(right_count);
            }
            Bounds3f left;
            std::size_t left_count = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                left.extend(bins[axis][b]);
                left_count += counts[axis][b];
                if (left_count == 0 || left_count == end - begin)
                    continue;
                const double cost = options_.traversal_cost +
                                    options_.intersection_cost *
                                        (left.surface_area() * static_cast<double>(left_count) +
                                         right_cost[b + 1]) /
                                        std::max(node_area, std::numeric_limits<double>::min());
                if (cost < best.cost) {
                    best.cost = cost;
                    best.axis = axis;
                    best.bin = b;
                }
            }
        }
        return best;
    }

    // A stable partition, as std::stable_partition's, that buffers only the
    // smaller side: std::stable_partition buffers the whole range, which at
    // the root is a second copy of every primitive, the build's peak memory.
    // The larger side is compacted in place, keeping its order.
    std::size_t partition(std::size_t begin, std::size_t end, const Bounds3f& centroids,
                          const Split& split) {
        std::vector<std::uint8_t> left(end - begin);
        std::size_t left_count = 0;
        for (std::size_t i = begin; i < end; ++i) {
            left[i - begin] = bin_of(primitives_[i].centroid, centroids, split.axis) <= split.bin;
            left_count += left[i - begin];
        }
        const std::size_t middle = begin + left_count;
        const bool buffer_left = left_count <= end - middle;
        std::vector<Primitive> buffer;
        buffer.reserve(buffer_left ? left_count : end - middle);
        if (buffer_left) { // the right side moves to the back, last first
            std::size_t to = end;
            for (std::size_t i = end; i-- > begin;)
                if (left[i - begin])
                    buffer.push_back(primitives_[i]);
                else
                    primitives_[--to] = primitives_[i];
            std::reverse_copy(buffer.begin(), buffer.end(),
                              primitives_.begin() + static_cast<std::ptrdiff_t>(begin));
        } else { // the left side moves to the front, first first
            std::size_t to = begin;
            for (std::size_t i = begin; i < end; ++i)
                if (left[i - begin])
                    primitives_[to++] = primitives_[i];
                else
                    buffer.push_back(primitives_[i]);
            std::copy(buffer.begin(), buffer.end(),
                      primitives_.begin() + static_cast<std::ptrdiff_t>(middle));
        }
        return middle;
    }

    std::vector<Primitive>& primitives_;
    const BvhBuildOptions& options_;
    std::atomic<int> spare_threads_{0};
};

// Depth-first layout: a node's first child follows it.
void flatten(const BuildNode& node, std::uint32_t depth, Bvh& out) {
    const auto index = static_cast<std::uint32_t>(out.nodes.size());
    out.nodes.emplace_back();
    out.nodes[index].bounds = node.bounds;
    out.stats.depth = std::max(out.stats.depth, depth);
    if (node.count > 0) {
        out.nodes[index].first_primitive = node.first;
        out.nodes[index].primitive_count = node.count;
        out.stats.leaves += 1;
        out.stats.largest_leaf = std::max(out.stats.largest_leaf, node.count);
        return;
    }
    flatten(*node.children[0], depth + 1, out);
    out.nodes[index].second_child = static_cast<std::uint32_t>(out.nodes.size());
    flatten(*node.children[1], depth + 1, out);
}

} // namespace

Bvh build_bvh(std::vector<Bounds3f> boxes, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    if (boxes.empty())
        return bvh;
    const std::size_t count = boxes.size();
    std::vector<Primitive> primitives(count);
    for (std::size_t i = 0; i < count; ++i)
        primitives[i] = {boxes[i], boxes[i].centroid(), static_cast<std::uint32_t>(i)};
    std::vector<Bounds3f>().swap(boxes);
    Builder builder(primitives, options);
    std::unique_ptr<BuildNode> root = builder.build(0, count, 0);
    // The leaf order out of the primitives, which are then freed before the
    // tree is laid out: the build's memory peaks once, not twice.
    bvh.primitives.resize(count);
    for (std::size_t i = 0; i < count; ++i)
        bvh.primitives[i] = primitives[i].index;
    std::vector<Primitive>().swap(primitives);
    bvh.nodes.reserve(2 * count);
    flatten(*root, 0, bvh);
    root.reset();
    bvh.stats.nodes = static_cast<std::uint32_t>(bvh.nodes.size());
    bvh.stats.sah_cost = bvh_sah_cost(bvh, options);
    bvh.stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

double bvh_sah_cost(const Bvh& bvh, const BvhBuildOptions& options) {
    if (bvh.nodes.empty())
        return 0.0;
    const double root_area = bvh.nodes[0].bounds.surface_area();
    if (!(root_area > 0.0))
        return options.intersection_cost * static_cast<double>(bvh.primitives.size());
    double cost = 0.0;
    for (const BvhNode& node : bvh.nodes) {
        const double weight = node.bounds.surface_area() / root_area;
        cost += node.is_leaf()
                    ? weight * options.intersection_cost * static_cast<double>(node.primitive_count)
                    : weight * options.traversal_cost;
    }
    return cost;
}

} // namespace wp
