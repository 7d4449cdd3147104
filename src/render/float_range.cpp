#include "render/float_range.hpp"

#include <algorithm>
#include <cmath>

namespace wp {

FloatFrame float_frame(const Scene& scene) {
    const SceneBox box = scene_box(scene);
    FloatFrame frame;
    double largest = box.largest_coordinate();
    // (A box of size 0 is a scene without shapes, as kernel tests build: only
    // the camera, which stays where it is.)
    if (box.size() > 0.0 && largest > kRecentreDistanceRatio * box.size()) {
        frame.origin = box.centre();
        largest = 0.5 * box.size();
    }
    if (!(largest > 0.0) || !std::isfinite(largest))
        return frame;
    int exponent = 0;
    std::frexp(largest, &exponent); // largest = m 2^exponent, m in [0.5, 1)
    if (exponent - 1 < kFloatRangeLowestExponent || exponent - 1 > kFloatRangeHighestExponent)
        frame.scale = std::ldexp(1.0, -exponent);
    return frame;
}

} // namespace wp
