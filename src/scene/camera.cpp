#include "scene/camera.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace wp {

namespace {

constexpr std::array<std::pair<FovAxis, const char*>, 5> kFovAxes{{{FovAxis::X, "x"},
                                                                   {FovAxis::Y, "y"},
                                                                   {FovAxis::Diagonal, "diagonal"},
                                                                   {FovAxis::Smaller, "smaller"},
                                                                   {FovAxis::Larger, "larger"}}};

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

} // namespace

std::optional<FovAxis> fov_axis_from_name(std::string_view name) {
    for (const auto& [axis, axis_name] : kFovAxes)
        if (name == axis_name)
            return axis;
    return std::nullopt;
}

const char* fov_axis_name(FovAxis axis) {
    for (const auto& [a, name] : kFovAxes)
        if (a == axis)
            return name;
    return "?";
}

std::string fov_axis_names() {
    std::string out;
    for (const auto& [axis, name] : kFovAxes)
        out += (out.empty() ? "" : ", ") + std::string(name);
    return out;
}

double vertical_fov_degrees(double fov_degrees, FovAxis axis, int width, int height) {
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    // Mitsuba resolves smaller and larger by aspect > 1 (a square is x, y).
    if (axis == FovAxis::Smaller)
        axis = aspect > 1.0 ? FovAxis::Y : FovAxis::X;
    else if (axis == FovAxis::Larger)
        axis = aspect > 1.0 ? FovAxis::X : FovAxis::Y;
    const double half = std::tan(0.5 * fov_degrees / kDegrees); // along the axis
    switch (axis) {
    case FovAxis::Y:
        return fov_degrees; // exactly as given: the default changes no image
    case FovAxis::X:
        return 2.0 * std::atan(half / aspect) * kDegrees;
    case FovAxis::Diagonal:
        // The diagonal's half-extent is the height's times sqrt(1 + aspect^2).
        return 2.0 * std::atan(half / std::sqrt(1.0 + aspect * aspect)) * kDegrees;
    case FovAxis::Smaller:
    case FovAxis::Larger:
        break;
    }
    return fov_degrees; // not reached: smaller and larger were resolved above
}

std::optional<FilterKind> filter_kind_from_name(std::string_view name) {
#define WP_FILTER_FROM_NAME(KIND, Name, name_, value, sampled)                                     \
    if (name == #name_)                                                                            \
        return FilterKind::Name;
    WP_FILTERS(WP_FILTER_FROM_NAME)
#undef WP_FILTER_FROM_NAME
    return std::nullopt;
}

const char* filter_kind_name(FilterKind kind) {
    switch (static_cast<wp_uint>(kind)) {
#define WP_FILTER_NAME_CASE(KIND, Name, name, value, sampled)                                      \
    case value:                                                                                    \
        return #name;
        WP_FILTERS(WP_FILTER_NAME_CASE)
#undef WP_FILTER_NAME_CASE
    default:
        return "?";
    }
}

std::string filter_kind_names() {
    std::string out;
#define WP_FILTER_LIST_NAME(KIND, Name, name, value, sampled)                                      \
    out += out.empty() ? #name : ", " #name;
    WP_FILTERS(WP_FILTER_LIST_NAME)
#undef WP_FILTER_LIST_NAME
    return out;
}

// The table's values are its rows' order.
#define WP_FILTER_VALUE_CHECK(KIND, Name, name, value, sampled)                                    \
    static_assert(static_cast<wp_uint>(FilterKind::Name) == WP_FILTER_##KIND);
WP_FILTERS(WP_FILTER_VALUE_CHECK)
#undef WP_FILTER_VALUE_CHECK

} // namespace wp
