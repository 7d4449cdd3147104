#include "scene/bvh.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <future>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

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
// More threads than this gain nothing at the sizes a scene has (the top
// levels stay serial) and each holds a partition buffer.
constexpr unsigned kMaxThreads = 16;

struct Primitive {
    Bounds3f bounds;
    glm::vec3 centroid;
    std::uint32_t index;
};

// A range of primitives with its boxes' bounds and its centroids' bounds:
// what a node needs before it is split. A parent computes its children's
// while it partitions (the primitives are read once a level, not twice).
struct PrimitiveRange {
    std::size_t begin = 0, end = 0;
    Bounds3f bounds, centroids;

    std::size_t count() const { return end - begin; }
};

struct Split {
    int axis = -1;
    int bin = 0; // primitives in bins [0, bin] go left
    double cost = std::numeric_limits<double>::infinity();
};

// A subtree's nodes in depth-first order, numbered from its own first node,
// and what flatten used to count.
struct Subtree {
    std::vector<BvhNode> nodes;
    std::uint32_t leaves = 0, depth = 0, largest_leaf = 0;

    // `other` after this subtree's nodes: its inner nodes' second children
    // move by the nodes before it.
    void append(const Subtree& other) {
        const auto offset = static_cast<std::uint32_t>(nodes.size());
        nodes.reserve(nodes.size() + other.nodes.size());
        for (BvhNode node : other.nodes) {
            if (!node.is_leaf())
                node.second_child += offset;
            nodes.push_back(node);
        }
        leaves += other.leaves;
        depth = std::max(depth, other.depth);
        largest_leaf = std::max(largest_leaf, other.largest_leaf);
    }
};

// What a thread's partitions reuse from node to node (one allocation per
// thread, not two per node).
struct Scratch {
    std::vector<std::uint8_t> left;
    std::vector<Primitive> buffer;
};

PrimitiveRange range_of(const std::vector<Primitive>& primitives, std::size_t begin,
                        std::size_t end) {
    PrimitiveRange r{begin, end, {}, {}};
    for (std::size_t i = begin; i < end; ++i) {
        r.bounds.extend(primitives[i].bounds);
        r.centroids.extend(primitives[i].centroid);
    }
    return r;
}

// Builds the tree straight into depth-first node arrays. A subtree built on
// another thread goes into an array of its own, as does its sibling, and the
// two are appended to their parent's array left first: the nodes' order is
// the tree's, never the threads' (one thread or sixteen give the same array).
class Builder {
  public:
    Builder(std::vector<Primitive>& primitives, const BvhBuildOptions& options, unsigned threads)
        : primitives_(primitives), options_(options) {
        spare_threads_ = static_cast<int>(threads) - 1;
    }

    void build(const PrimitiveRange& range, std::uint32_t depth, Subtree& out, Scratch& scratch) {
        const auto index = out.nodes.size();
        out.nodes.emplace_back();
        out.nodes[index].bounds = range.bounds;
        const std::size_t count = range.count();
        auto make_leaf = [&] {
            out.nodes[index].first_primitive = static_cast<std::uint32_t>(range.begin);
            out.nodes[index].primitive_count = static_cast<std::uint32_t>(count);
            out.leaves += 1;
            out.depth = std::max(out.depth, depth);
            out.largest_leaf = std::max(out.largest_leaf, static_cast<std::uint32_t>(count));
        };
        if (count <= options_.max_leaf_size || depth >= options_.max_depth)
            return make_leaf();

        const Split split = best_split(range);
        const double leaf_cost = options_.intersection_cost * static_cast<double>(count);
        // A leaf when no plane separates the centroids, or when a leaf is
        // cheaper and small enough to stay fast in the worst case.
        if (split.axis < 0 || (split.cost >= leaf_cost && count <= 4 * options_.max_leaf_size))
            return make_leaf();

        auto [left, right] = partition(range, split, scratch);
        if (left.count() == 0 || right.count() == 0) { // centroids too close for the bins
            const std::size_t middle = range.begin + count / 2;
            const int axis = split.axis;
            std::nth_element(primitives_.begin() + static_cast<std::ptrdiff_t>(range.begin),
                             primitives_.begin() + static_cast<std::ptrdiff_t>(middle),
                             primitives_.begin() + static_cast<std::ptrdiff_t>(range.end),
                             [axis](const Primitive& a, const Primitive& b) {
                                 return a.centroid[axis] < b.centroid[axis] ||
                                        (a.centroid[axis] == b.centroid[axis] && a.index < b.index);
                             });
            left = range_of(primitives_, range.begin, middle);
            right = range_of(primitives_, middle, range.end);
        }

        // The left child on another thread, if one is free; both children
        // then go into arrays of their own, appended in order.
        if (std::min(left.count(), right.count()) >= options_.parallel_subtree && take_thread()) {
            auto left_async = std::async(std::launch::async, [this, left = left, depth] {
                Subtree subtree;
                Scratch own;
                build(left, depth + 1, subtree, own);
                ++spare_threads_;
                return subtree;
            });
            Subtree right_subtree;
            build(right, depth + 1, right_subtree, scratch);
            const Subtree left_subtree = left_async.get();
            out.append(left_subtree);
            out.nodes[index].second_child = static_cast<std::uint32_t>(out.nodes.size());
            out.append(right_subtree);
            return;
        }
        build(left, depth + 1, out, scratch);
        out.nodes[index].second_child = static_cast<std::uint32_t>(out.nodes.size());
        build(right, depth + 1, out, scratch);
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
    Split best_split(const PrimitiveRange& range) const {
        Split best;
        const Bounds3f& centroids = range.centroids;
        const double node_area = range.bounds.surface_area();
        bool splittable[3];
        for (int axis = 0; axis < 3; ++axis)
            splittable[axis] = centroids.upper[axis] > centroids.lower[axis];
        if (!splittable[0] && !splittable[1] && !splittable[2])
            return best;
        std::array<std::array<Bounds3f, kBins>, 3> bins;
        std::array<std::array<std::size_t, kBins>, 3> counts{};
        for (std::size_t i = range.begin; i < range.end; ++i) {
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
                if (left_count == 0 || left_count == range.count())
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
    // The larger side is compacted in place, keeping its order. The pass
    // that sorts the primitives to their sides also bounds each side.
    std::pair<PrimitiveRange, PrimitiveRange> partition(const PrimitiveRange& range,
                                                        const Split& split, Scratch& scratch) {
        const std::size_t begin = range.begin, end = range.end;
        std::vector<std::uint8_t>& left = scratch.left;
        left.resize(end - begin);
        PrimitiveRange l, r;
        std::size_t left_count = 0;
        for (std::size_t i = begin; i < end; ++i) {
            const Primitive& p = primitives_[i];
            const bool is_left = bin_of(p.centroid, range.centroids, split.axis) <= split.bin;
            left[i - begin] = is_left;
            left_count += is_left;
            PrimitiveRange& side = is_left ? l : r;
            side.bounds.extend(p.bounds);
            side.centroids.extend(p.centroid);
        }
        const std::size_t middle = begin + left_count;
        l.begin = begin;
        l.end = middle;
        r.begin = middle;
        r.end = end;
        const bool buffer_left = left_count <= end - middle;
        std::vector<Primitive>& buffer = scratch.buffer;
        buffer.clear();
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
        return {l, r};
    }

    std::vector<Primitive>& primitives_;
    const BvhBuildOptions& options_;
    std::atomic<int> spare_threads_{0};
};

// The number of threads a build uses: the options', else
// WAVEPATH_BVH_THREADS (1 forces a serial build, e.g. to compare), else the
// machine's; at most kMaxThreads.
unsigned build_threads(const BvhBuildOptions& options) {
    unsigned threads = options.threads;
    if (threads == 0)
        if (const char* text = std::getenv("WAVEPATH_BVH_THREADS")) {
            char* end = nullptr;
            const long value = std::strtol(text, &end, 10);
            if (end == text || *end != '\0' || value < 1 || value > 1024)
                throw std::invalid_argument(
                    std::string(
                        "WAVEPATH_BVH_THREADS must be a whole number from 1 to 1024, got '") +
                    text + "'");
            threads = static_cast<unsigned>(value);
        }
    if (threads == 0)
        threads = std::thread::hardware_concurrency();
    return std::clamp(threads, 1u, kMaxThreads);
}

} // namespace

Bvh build_bvh(std::vector<Bounds3f> boxes, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    if (boxes.empty())
        return bvh;
    const unsigned threads = build_threads(options);
    const std::size_t count = boxes.size();
    std::vector<Primitive> primitives(count);
    for (std::size_t i = 0; i < count; ++i)
        primitives[i] = {boxes[i], boxes[i].centroid(), static_cast<std::uint32_t>(i)};
    std::vector<Bounds3f>().swap(boxes);
    Subtree tree;
    {
        Scratch scratch;
        Builder(primitives, options, threads)
            .build(range_of(primitives, 0, count), 0, tree, scratch);
    }
    // The leaf order out of the primitives, which are then freed.
    bvh.primitives.resize(count);
    for (std::size_t i = 0; i < count; ++i)
        bvh.primitives[i] = primitives[i].index;
    std::vector<Primitive>().swap(primitives);
    bvh.nodes = std::move(tree.nodes);
    bvh.stats.nodes = static_cast<std::uint32_t>(bvh.nodes.size());
    bvh.stats.leaves = tree.leaves;
    bvh.stats.depth = tree.depth;
    bvh.stats.largest_leaf = tree.largest_leaf;
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
