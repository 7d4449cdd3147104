// Limits and checks shared by the JSON loader and by code that builds a
// wp::Scene directly (tests, generated stress scenes).
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace wp {

namespace scene_limits {
// Largest magnitude accepted for a coordinate or radius. (The renderer moves
// and rescales a scene into float32's comfortable range exactly before it
// renders, render/float_range.hpp, so this is the format's limit, not
// float32's: every scale within it renders the same image.)
inline constexpr double max_coordinate = 1e30;
// Smallest accepted scene size (the longest side of the box around shapes
// and eye): the zero-area check squares a triangle's doubled area, a length
// to the fourth power, and for features a millionth of the size that stays
// a normal double (above 2.2e-308) down to here.
inline constexpr double min_scene_size = 1e-60;
// Largest accepted ratio of a scene's distance from the origin (its largest
// coordinate) to its size: 2^29. Coordinates are held in double (53 bits)
// and rendered in float32 (24 bits) relative to the scene's own box, so
// beyond 2^(53 - 24) times its size a coordinate's double rounding alone is
// coarser than float32's resolution of the scene: its detail is already
// lost in the input (the coordinates would need more than 16 digits).
inline constexpr double max_distance_to_size = 536870912.0; // 2^29
// Largest accepted emitted radiance per channel.
inline constexpr double max_radiance = 1e30;
// Largest conductor eta or k: the Fresnel term squares them twice in float32,
// and measured metals stay below 100.
inline constexpr double max_index = 1e4;
// Largest microfacet roughness alpha (the kernels floor it at 1e-4, as
// Mitsuba does); past 1 a surface is rougher than any measured one.
inline constexpr double max_alpha = 4.0;
// Largest pixel filter size (a tent's radius, a Gaussian's standard
// deviation), in pixels: past it a pixel averages most of a small image.
inline constexpr double max_filter_size = 64.0;
// Largest image side in pixels.
inline constexpr int max_resolution = 16384;
// A triangle is zero-area when |cross(e1, e2)| <= this * (longest edge)^2.
inline constexpr double zero_area_relative = 1e-12;
// Quad corners must lie within this * (largest corner distance) of one plane.
inline constexpr double quad_planarity_relative = 1e-6;
// up is "parallel" to the view direction when |cross(d, up)| <= this * |d| * |up|.
inline constexpr double up_parallel_relative = 1e-6;
// eye and look_at "coincide" when |look_at - eye| <= this * max(|eye|, |look_at|).
inline constexpr double eye_look_at_relative = 1e-9;
} // namespace scene_limits

// True when the triangle (a, b, c) has zero area in the sense above (exactly
// zero, or |cross(b - a, c - a)| <= 1e-12 * longest edge^2).
bool is_zero_area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// True when look_at is (numerically) the eye, so there is no view direction.
bool view_direction_is_degenerate(const glm::dvec3& eye, const glm::dvec3& look_at);

// True when up is zero or (numerically) parallel to look_at - eye.
bool up_is_parallel(const glm::dvec3& eye, const glm::dvec3& look_at, const glm::dvec3& up);

// True when m is a rotation: orthonormal columns (to 1e-6) and determinant
// +1 (no mirror).
bool is_rotation(const glm::dmat3& m);

// True when some triangle or sphere has an emissive material or some emitter
// (point, spot, directional, constant, envmap) is not black. Light comes only
// from those, so a scene without one renders black.
bool has_emitter(const Scene& scene);

// Checks a complete Scene against every rule the loader enforces (finite values
// within the limits above, reflectance in [0, 1], non-negative emission, positive
// radius, resolution 1..16384, fov in (0, 180), a usable camera frame, material
// indices in range, no emissive sphere, no zero-area triangle, at least one
// shape, a scene size and a distance from the origin that float32 rendering
// can resolve: docs/stability.md, "Accepted range"). Throws SceneError("<source>: <field>:
// <problem>") naming the field in C++ terms, e.g. "triangles[3].v[1]". parse_scene() calls it as a
// final check.
void validate_scene(const Scene& scene);

} // namespace wp
