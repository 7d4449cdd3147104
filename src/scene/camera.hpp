// The camera's conventions on the host: Mitsuba's fov_axis, and the names of
// the pixel filters (the rows of WP_FILTERS, kernels/wp_shared.h).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "scene/scene.hpp"

namespace wp {

// The axis along which a scene file's `fov` is measured, as Mitsuba 3's
// perspective sensors name them: the image's width (x), its height (y), its
// diagonal, or the smaller or larger of width and height (a square image's
// smaller axis is x and its larger y, as in Mitsuba; both give the same
// angle there). wavepath's default is y, the vertical angle its `fov` always
// meant (Mitsuba's default is x).
enum class FovAxis { X, Y, Diagonal, Smaller, Larger };

std::optional<FovAxis> fov_axis_from_name(std::string_view name);
const char* fov_axis_name(FovAxis axis);
// "x, y, diagonal, smaller, larger", for messages.
std::string fov_axis_names();

// The vertical full field of view, in degrees, of an image of width x height
// pixels whose full field of view along `axis` is `fov_degrees`: the image
// plane at unit distance has half-extents tan(fov/2) along the axis, and the
// aspect ratio width / height relates the three axes (Mitsuba's parse_fov).
// In (0, 180) for fov_degrees in (0, 180).
double vertical_fov_degrees(double fov_degrees, FovAxis axis, int width, int height);

// The filter named `name` in a scene file ("box", "tent", "gaussian").
std::optional<FilterKind> filter_kind_from_name(std::string_view name);
const char* filter_kind_name(FilterKind kind);
// "box, tent, gaussian", for messages.
std::string filter_kind_names();

} // namespace wp
