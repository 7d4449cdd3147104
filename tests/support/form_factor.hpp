// Closed-form form factors for the analytic tests (irradiance from a square
// light, directly or by way of a mirror).
#pragma once

#include <cmath>

namespace wp::test {

// Form factor from a differential area at the origin (normal +z) to the
// rectangle [0, a] x [0, b] in the plane z = c, parallel to it. Odd in a and
// in b, so rectangles not touching the axis follow by superposition.
inline double corner_form_factor(double a, double b, double c) {
    double x = a / c, y = b / c;
    double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * M_PI);
}

// The same to the rectangle [x0, x1] x [y0, y1] at height c.
inline double rectangle_form_factor(double x0, double x1, double y0, double y1, double c) {
    return corner_form_factor(x1, y1, c) - corner_form_factor(x0, y1, c) -
           corner_form_factor(x1, y0, c) + corner_form_factor(x0, y0, c);
}

} // namespace wp::test
