// An affine object-to-world transform in double precision, built from steps
// (translate, rotate, look-at, scale, raw matrix) that compose in list order.
//
// Composition order: compose({A, B, C}) applies A first, then B, then C to the
// object's points, i.e. its matrix is C * B * A. So a list reads as a recipe:
// "scale the bunny, rotate it, then move it into place". (pbrt's scene files
// accumulate the other way, post-multiplying the current transform; a list that
// reads in the order things happen is harder to get wrong in JSON.)
//
// Normals transform by the inverse transpose of the linear part and are then
// normalised: under a non-uniform scale this keeps them perpendicular to the
// transformed surface. A transform with negative determinant mirrors the object;
// mesh code then reverses each triangle's winding (flips_orientation()).
#pragma once

#include <array>
#include <span>
#include <stdexcept>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace wp {

// Thrown by the factories below for arguments that give no invertible affine
// transform. what() is one line naming the step, e.g. "rotate: axis has zero length".
class TransformError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

class Transform {
  public:
    Transform() = default; // the identity

    static Transform translate(const glm::dvec3& offset);
    // Rotation by `degrees` about `axis` (any non-zero length) through the origin,
    // right-handed: counter-clockwise when the axis points at the viewer.
    static Transform rotate(double degrees, const glm::dvec3& axis);
    static Transform scale(double factor);             // uniform; factor must be non-zero
    static Transform scale(const glm::dvec3& factors); // per axis; each non-zero
    // Places the object at `from`, turned so that its local +z axis points at `to`
    // and its local +y axis is as close to `up` as possible (its +x is y cross z).
    // This is a camera-to-world style placement, the inverse of pbrt's LookAt.
    static Transform look_at(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& up);
    // A matrix written row by row, as on paper: rows[r * 4 + c] is row r, column c,
    // so the translation is rows[3], rows[7], rows[11]. The last row must be
    // 0 0 0 1 (affine only) and the 3x3 part invertible.
    static Transform from_rows(const std::array<double, 16>& rows);

    // Applies `steps` in list order: the first step acts on the object first.
    static Transform compose(std::span<const Transform> steps);

    // This transform followed by `next` (matrix next * this).
    Transform then(const Transform& next) const;

    glm::dvec3 apply_to_point(const glm::dvec3& p) const;
    glm::dvec3 apply_to_vector(const glm::dvec3& v) const; // no translation
    // Inverse transpose, then normalised. The input need not be unit length.
    glm::dvec3 apply_to_normal(const glm::dvec3& n) const;

    // True when the transform mirrors (negative determinant).
    bool flips_orientation() const;
    bool is_identity() const;

    const glm::dmat4& matrix() const { return m_; }
    const glm::dmat4& inverse() const { return inv_; }

  private:
    Transform(const glm::dmat4& m, const glm::dmat4& inv) : m_(m), inv_(inv) {}
    // Checks finiteness, the affine last row and invertibility; `step` names the
    // factory in the message.
    static Transform checked(const glm::dmat4& m, const char* step);

    glm::dmat4 m_{1.0};
    glm::dmat4 inv_{1.0};
};

} // namespace wp
