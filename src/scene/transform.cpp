#include "scene/transform.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace wp {

namespace {

// The 3x3 part counts as singular when |det| <= this * the product of its column
// lengths (Hadamard's bound on |det|): relative, so a tiny but honest scale such as
// 1e-6 passes while a flattening one (two columns parallel) does not.
constexpr double singular_relative = 1e-12;

// Directions count as parallel when |cross(a, b)| <= this * |a| * |b|.
constexpr double parallel_relative = 1e-9;

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// |v| without overflow for components near the double range.
double robust_length(const glm::dvec3& v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return m > 0.0 ? m * glm::length(v / m) : 0.0;
}

glm::dmat3 linear_part(const glm::dmat4& m) {
    return glm::dmat3(m);
}

} // namespace

Transform Transform::checked(const glm::dmat4& m, const char* step) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                throw TransformError(std::string(step) + ": matrix entry is not finite");
    // glm is column-major: m[c][r]. The last row is m[0][3], m[1][3], m[2][3], m[3][3].
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
        throw TransformError(std::string(step) +
                             ": last row must be 0 0 0 1 (only affine transforms)");
    // The determinant of the columns scaled to unit length is det / (Hadamard's
    // bound), computed without over- or underflow for huge or tiny scales.
    glm::dmat3 a = linear_part(m);
    bool zero_column = false;
    for (int c = 0; c < 3; ++c) {
        const double len = robust_length(a[c]);
        zero_column |= !(len > 0.0);
        a[c] /= len;
    }
    if (zero_column || std::abs(glm::determinant(a)) <= singular_relative)
        throw TransformError(std::string(step) + ": transform is singular (it flattens the "
                                                 "object, so normals cannot be transformed)");
    return Transform(m, glm::inverse(m));
}

Transform Transform::translate(const glm::dvec3& offset) {
    if (!finite(offset))
        throw TransformError("translate: offset is not finite");
    return checked(glm::translate(glm::dmat4(1.0), offset), "translate");
}

Transform Transform::rotate(double degrees, const glm::dvec3& axis) {
    if (!std::isfinite(degrees) || !finite(axis))
        throw TransformError("rotate: angle or axis is not finite");
    const double len = glm::length(axis);
    if (!(len > 0.0))
        throw TransformError("rotate: axis has zero length");
    // glm::rotate builds the right-handed (Rodrigues) rotation about the normalised axis.
    return checked(glm::rotate(glm::dmat4(1.0), glm::radians(degrees), axis / len), "rotate");
}

Transform Transform::scale(double factor) {
    return scale(glm::dvec3(factor));
}

Transform Transform::scale(const glm::dvec3& factors) {
    if (!finite(factors))
        throw TransformError("scale: factor is not finite");
    if (factors.x == 0.0 || factors.y == 0.0 || factors.z == 0.0)
        throw TransformError("scale: factor must be non-zero");
    return checked(glm::scale(glm::dmat4(1.0), factors), "scale");
}

Transform Transform::look_at(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& up) {
    if (!finite(from) || !finite(to) || !finite(up))
        throw TransformError("look_at: from, to or up is not finite");
    const glm::dvec3 d = to - from;
    const double dlen = glm::length(d);
    if (!(dlen > 0.0))
        throw TransformError("look_at: 'to' equals 'from'");
    const double c = glm::length(glm::cross(d, up));
    if (c == 0.0 || c <= parallel_relative * dlen * glm::length(up))
        throw TransformError("look_at: 'up' is zero or parallel to the direction 'to' - 'from'");
    const glm::dvec3 z = d / dlen;
    const glm::dvec3 x = glm::normalize(glm::cross(up, z)); // y cross z, with y ~ up
    const glm::dvec3 y = glm::cross(z, x);
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(x, 0.0);
    m[1] = glm::dvec4(y, 0.0);
    m[2] = glm::dvec4(z, 0.0);
    m[3] = glm::dvec4(from, 1.0);
    return checked(m, "look_at");
}

Transform Transform::from_rows(const std::array<double, 16>& rows) {
    glm::dmat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            m[c][r] = rows[static_cast<std::size_t>(r * 4 + c)];
    return checked(m, "matrix");
}

Transform Transform::compose(std::span<const Transform> steps) {
    Transform t;
    for (const Transform& s : steps)
        t = t.then(s);
    return t;
}

Transform Transform::then(const Transform& next) const {
    // (next * this)^-1 = this^-1 * next^-1: no new inversion, no new rounding.
    return Transform(next.m_ * m_, inv_ * next.inv_);
}

glm::dvec3 Transform::apply_to_point(const glm::dvec3& p) const {
    return glm::dvec3(m_ * glm::dvec4(p, 1.0));
}

glm::dvec3 Transform::apply_to_vector(const glm::dvec3& v) const {
    return linear_part(m_) * v;
}

glm::dvec3 Transform::apply_to_normal(const glm::dvec3& n) const {
    // (A^-1)^T n: the transpose is folded into the product order.
    return glm::normalize(n * linear_part(inv_));
}

bool Transform::flips_orientation() const {
    return glm::determinant(linear_part(m_)) < 0.0;
}

bool Transform::is_identity() const {
    return m_ == glm::dmat4(1.0);
}

} // namespace wp
