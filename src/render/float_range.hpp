// Keeping a scene's coordinates where float32 arithmetic works.
//
// The kernels' intersection tests form products of up to three coordinate
// differences: the watertight triangle test's scaled distance T is a
// coordinate cubed (kernels/triangle.h), its determinant one squared, a
// light's area and the squared distance of next-event estimation too. With
// coordinates near 1e12 the cube overflows float32 (3.4e38) and with
// coordinates near 1e-13 it falls below the smallest normal float (1.2e-38)
// and flushes to zero: the hexroom scaled by 1e12 rendered 2.4 times too
// bright, scaled by 1e-15 black. And a scene far from the origin compared
// with its size loses its detail to float32's spacing there: the hexroom
// moved by 1e6 rendered 62 % dark (docs/stability.md, "Accepted range").
//
// A path tracer's image depends neither on the scene's units nor on where
// its origin is. So flatten_scene maps every point p to scale (p - origin)
// in double before rounding to float32: `origin` the centre of the scene's
// box when the scene lies far from the origin compared with its size, and
// `scale` the power of two that brings the largest coordinate near 1 when it
// lies outside a comfortable band. A power of two is exact in double and in
// float32, and so every kernel quantity scales by an exact power of two: the
// image is the one of the scene at its normalised size, bit for bit. Scenes
// that need neither are left exactly as they are (origin 0, scale 1), and
// so are their images.
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene.hpp"
#include "scene/scene_box.hpp"

namespace wp {

// The band of largest coordinate magnitudes left unscaled: [2^-10, 2^20].
// Within it a coordinate cubed stays far from float32's limits, and so does
// the cube of a feature a float32 ulp of the largest coordinate in size.
inline constexpr int kFloatRangeLowestExponent = -10;
inline constexpr int kFloatRangeHighestExponent = 20;
// Scenes whose largest coordinate is more than this many times their size
// are moved to the origin. (Moving a scene rounds its coordinates anew, so
// scenes nearer than this keep their exact images: the stress scene
// translate-1e5, the hexroom 6250 times its size from the origin, renders
// within noise of the original without the move.)
inline constexpr double kRecentreDistanceRatio = 16384.0; // 2^14

// Where the kernels' coordinates come from: a point p of the scene becomes
// scale * (p - origin), a radius or length scale * r.
struct FloatFrame {
    glm::dvec3 origin{0.0};
    double scale = 1.0;
    glm::dvec3 point(const glm::dvec3& p) const { return scale * (p - origin); }
};
FloatFrame float_frame(const Scene& scene);

} // namespace wp
