// The quantised child boxes of a four-wide node (render/quantised_node.hpp):
// every child's float box lies inside its decoded box, decoded in float as
// the kernel decodes it, on random boxes at every scale and offset and on
// degenerate ones (flat, huge, infinite, NaN); and a finite box grows by at
// most a step or two of its node's grid.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "render/quantised_node.hpp"

using namespace wp;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The step of an axis of the node (2^(exponent - 127)).
float step(wp_uchar exponent) {
    return std::ldexp(1.0f, static_cast<int>(exponent) - 127);
}

// Quantises `count` boxes and checks that each decoded box holds its float
// box: per axis, lower <= the true lower and upper >= the true upper, or
// both decoded bounds NaN (an axis the slab test does not limit).
void check_contains(const Bounds3f* boxes, int count, const std::string& what) {
    WpBvhNode node{};
    quantise_child_boxes(boxes, count, node);
    for (int i = 0; i < count; ++i) {
        const Bounds3f got = decoded_child_box(node, i);
        for (int axis = 0; axis < 3; ++axis) {
            INFO(what << ": child " << i << " axis " << axis << ": [" << boxes[i].lower[axis]
                      << ", " << boxes[i].upper[axis] << "] decoded as [" << got.lower[axis] << ", "
                      << got.upper[axis] << "]");
            const bool unlimited = std::isnan(got.lower[axis]) && std::isnan(got.upper[axis]);
            CHECK((unlimited || (got.lower[axis] <= boxes[i].lower[axis] &&
                                 got.upper[axis] >= boxes[i].upper[axis])));
        }
    }
}

} // namespace

TEST_CASE("quantised nodes: random boxes at every scale and offset lie inside their decoded "
          "boxes, which are at most two steps larger a side") {
    std::mt19937 generator(35);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> scale_power(-30, 30), children(1, 4);
    for (int trial = 0; trial < 20000; ++trial) {
        const float offset = (unit(generator) - 0.5f) * std::ldexp(1.0f, scale_power(generator));
        const float size = std::ldexp(1.0f, scale_power(generator));
        const int count = children(generator);
        Bounds3f boxes[4];
        for (int i = 0; i < count; ++i)
            for (int axis = 0; axis < 3; ++axis) {
                const float a = offset + size * unit(generator);
                const float b = trial % 7 == 0 ? a : offset + size * unit(generator); // flat
                boxes[i].lower[axis] = std::min(a, b);
                boxes[i].upper[axis] = std::max(a, b);
            }
        check_contains(boxes, count, "trial " + std::to_string(trial));
        WpBvhNode node{};
        quantise_child_boxes(boxes, count, node);
        const wp_uchar exponents[3] = {node.exponent_x, node.exponent_y, node.exponent_z};
        for (int i = 0; i < count; ++i) {
            const Bounds3f got = decoded_child_box(node, i);
            for (int axis = 0; axis < 3; ++axis) {
                // A step of the grid, plus the decode's rounding (half an ulp
                // of the coordinate) on the box's side.
                const float slack =
                    2.0f * step(exponents[axis]) +
                    std::ldexp(std::abs(offset) + size, -22); // a few ulps of the coordinates
                INFO("trial " << trial << " child " << i << " axis " << axis);
                CHECK(boxes[i].lower[axis] - got.lower[axis] <= slack);
                CHECK(got.upper[axis] - boxes[i].upper[axis] <= slack);
            }
        }
    }
}

TEST_CASE("quantised nodes: degenerate boxes (flat, huge, tiny, infinite, NaN, empty) lie "
          "inside their decoded boxes") {
    const float big = std::numeric_limits<float>::max();
    const float tiny = std::numeric_limits<float>::denorm_min();
    auto box = [](float lx, float ly, float lz, float ux, float uy, float uz) {
        Bounds3f b;
        b.lower = glm::vec3(lx, ly, lz);
        b.upper = glm::vec3(ux, uy, uz);
        return b;
    };
    const Bounds3f flat[2] = {box(1, 2, 3, 1, 2, 3), box(1, 2, 3, 1, 5, 3)};
    check_contains(flat, 2, "points and flat boxes");
    const Bounds3f huge[3] = {box(-big, -big, 0, big, big, 1), box(-big, 0, 0, -big, 1, 1),
                              box(big, big, big, big, big, big)};
    check_contains(huge, 3, "boxes spanning all floats (the extent overflows a float)");
    const Bounds3f subnormal[2] = {box(0, -tiny, tiny, tiny, tiny, 2 * tiny),
                                   box(-tiny, 0, 0, 0, 3 * tiny, 3 * tiny)};
    check_contains(subnormal, 2, "subnormal boxes");
    const Bounds3f far_small[2] = {
        box(1e7f, -1e7f, 3e30f, 1e7f + 1, -1e7f + 1, 3e30f),
        box(1e7f + 0.5f, -1e7f, 3.0000001e30f, 1e7f + 2, -1e7f + 8, 3.0000001e30f)};
    check_contains(far_small, 2, "small boxes far from the origin");
    const Bounds3f infinite[2] = {box(-kInf, 0, 0, 1, 1, 1), box(0, 0, 0, 1, kInf, 1)};
    check_contains(infinite, 2, "infinite bounds");
    const Bounds3f nan[2] = {box(kNaN, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, kNaN)};
    check_contains(nan, 2, "NaN bounds");
    const Bounds3f empty[2] = {Bounds3f{}, box(0, 0, 0, 1, 1, 1)};
    check_contains(empty, 2, "an empty box beside a finite one");
    // A finite node away from the ends of the float range decodes to finite
    // boxes (only the degenerate axes above fall back to NaN or overflow).
    WpBvhNode node{};
    quantise_child_boxes(far_small, 2, node);
    for (int i = 0; i < 2; ++i) {
        const Bounds3f got = decoded_child_box(node, i);
        for (int axis = 0; axis < 3; ++axis) {
            CHECK(std::isfinite(got.lower[axis]));
            CHECK(std::isfinite(got.upper[axis]));
        }
    }
}
