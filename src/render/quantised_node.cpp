#include "render/quantised_node.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace wp {

static_assert(sizeof(WpBvhNode) == 64, "a node is one cache line");

namespace {

// 2^(exponent - 127): the float with these exponent bits, as the kernel
// makes it (as_float(exponent << 23)). exponent 1 .. 254, normal floats only.
float step_of(wp_uchar exponent) {
    return std::bit_cast<float>(static_cast<std::uint32_t>(exponent) << 23);
}

// origin + q * step, as the kernel computes it: q * step is exact (q has 8
// significant bits and step is a power of two at least 2^-126; at the top of
// the range it may overflow to infinity, alike on both sides), so the one
// rounding is the addition's, with or without FMA.
float decode(float origin, wp_uchar q, float step) {
    return origin + static_cast<float>(q) * step;
}

// One axis of a node: origin and exponent for the children's bounds
// lower[i] .. upper[i], i < count, and their 8-bit steps.
struct AxisCode {
    float origin = 0.0f;
    wp_uchar exponent = 127; // step 1
    wp_uchar lower[4] = {0, 0, 0, 0};
    wp_uchar upper[4] = {0, 0, 0, 0};
};

AxisCode quantise_axis(const float* lower, const float* upper, int count) {
    AxisCode code;
    float low = std::numeric_limits<float>::infinity();
    float high = -std::numeric_limits<float>::infinity();
    bool finite = count > 0;
    for (int i = 0; i < count; ++i) {
        finite = finite && std::isfinite(lower[i]) && std::isfinite(upper[i]);
        low = std::min(low, lower[i]);
        high = std::max(high, upper[i]);
    }
    if (!finite || !(low <= high)) {
        // An infinite, NaN or inverted (empty) box somewhere: the whole axis
        // decodes to NaN, which limits no child (kernels/bvh.h's slab test).
        code.origin = count > 0 ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
        return code;
    }
    code.origin = low;
    // The smallest step with low + 255 step >= high (exactly, hence also once
    // rounded, high being a float), at least 2^-126 and at most 2^127: every
    // finite extent (under 2^129) fits 255 steps of 2^127.
    const double extent = static_cast<double>(high) - static_cast<double>(low);
    int power = 0;
    const double mantissa = std::frexp(extent / 255.0, &power); // extent / 255 = m 2^power
    int exponent = std::clamp(power - (mantissa == 0.5 ? 1 : 0) + 127, 1, 254);
    while (exponent < 254 && std::ldexp(255.0, exponent - 127) < extent)
        ++exponent; // extent / 255 rounded down
    code.exponent = static_cast<wp_uchar>(exponent);
    const float step = step_of(code.exponent);
    for (int i = 0; i < count; ++i) {
        // The estimate, then moved outward until the decode, rounded as the
        // kernel rounds it, holds the bound: decode is monotonic in q, q = 0
        // gives low <= lower[i] and q = 255 gives at least high >= upper[i].
        double q = std::floor((static_cast<double>(lower[i]) - low) / step);
        int ql = static_cast<int>(std::clamp(q, 0.0, 255.0));
        while (ql > 0 && decode(low, static_cast<wp_uchar>(ql), step) > lower[i])
            --ql;
        q = std::ceil((static_cast<double>(upper[i]) - low) / step);
        int qu = static_cast<int>(std::clamp(q, 0.0, 255.0));
        while (qu < 255 && decode(low, static_cast<wp_uchar>(qu), step) < upper[i])
            ++qu;
        code.lower[i] = static_cast<wp_uchar>(ql);
        code.upper[i] = static_cast<wp_uchar>(qu);
    }
    return code;
}

} // namespace

void quantise_child_boxes(const Bounds3f* boxes, int count, WpBvhNode& node) {
    float lower[4], upper[4];
    AxisCode axes[3];
    for (int axis = 0; axis < 3; ++axis) {
        for (int i = 0; i < count; ++i) {
            lower[i] = boxes[i].lower[axis];
            upper[i] = boxes[i].upper[axis];
        }
        axes[axis] = quantise_axis(lower, upper, count);
    }
    node.origin_x = axes[0].origin;
    node.origin_y = axes[1].origin;
    node.origin_z = axes[2].origin;
    node.exponent_x = axes[0].exponent;
    node.exponent_y = axes[1].exponent;
    node.exponent_z = axes[2].exponent;
    node.pad0 = 0;
    for (int i = 0; i < 4; ++i) {
        node.lower_x[i] = axes[0].lower[i];
        node.upper_x[i] = axes[0].upper[i];
        node.lower_y[i] = axes[1].lower[i];
        node.upper_y[i] = axes[1].upper[i];
        node.lower_z[i] = axes[2].lower[i];
        node.upper_z[i] = axes[2].upper[i];
    }
}

Bounds3f decoded_child_box(const WpBvhNode& node, int i) {
    Bounds3f b;
    b.lower.x = decode(node.origin_x, node.lower_x[i], step_of(node.exponent_x));
    b.lower.y = decode(node.origin_y, node.lower_y[i], step_of(node.exponent_y));
    b.lower.z = decode(node.origin_z, node.lower_z[i], step_of(node.exponent_z));
    b.upper.x = decode(node.origin_x, node.upper_x[i], step_of(node.exponent_x));
    b.upper.y = decode(node.origin_y, node.upper_y[i], step_of(node.exponent_y));
    b.upper.z = decode(node.origin_z, node.upper_z[i], step_of(node.exponent_z));
    return b;
}

} // namespace wp
