// An envmap emitter's image as the kernels read it, its sampling tables, and
// the double-precision reference of both (kernels/lights/envmap.h has the
// conventions, Mitsuba 3.9.1's; tests/kernels/test_envmap.cpp compares the
// device with this reference).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "image/texture_image.hpp"

namespace wp {

struct EnvironmentTables {
    // The image, padded to at least 2 x 3 texels by repeating its last
    // column and row (as Mitsuba pads it), linear RGB, row 0 at the zenith.
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<float> rgb; // 3 per texel, rows one after another
    // The sampling tables: height - 1 cumulative row probabilities, then for
    // each row its width cumulative patch probabilities, each table ending
    // in exactly 1; then for each row j two floats, cos(theta_j) and
    // cos(theta_j) - cos(theta_{j+1}) (theta_j = pi j / (height - 1)).
    // Empty when the image is black (nothing to sample).
    std::vector<float> cdf;
    // The integral over the sphere of directions of the channels' mean
    // radiance (before the emitter's scale): what the light's power is
    // estimated from.
    double integral = 0.0;

    glm::dvec3 texel(std::uint32_t x, std::uint32_t y) const;
    // In double precision, by the kernels' rules: the radiance seen looking
    // along the unit direction `local` in the map's frame (before the
    // scale), and the density of the tables' sampling there (0 where it
    // never samples).
    glm::dvec3 radiance(const glm::dvec3& local) const;
    double pdf(const glm::dvec3& local) const;
};

// Builds the tables of `image`.
EnvironmentTables build_environment_tables(const TextureImage& image);

// The bilinear patch of a width x height map that the map-frame direction
// `local` falls in (kernels/lights/envmap.h, wp_envmap_patch): columns *i and
// *i + 1 mod width with the second's weight *ax, rows *j, *j + 1 with *ay.
void environment_patch(std::uint32_t width, std::uint32_t height, const glm::dvec3& local,
                       std::uint32_t* i, std::uint32_t* j, double* ax, double* ay);

} // namespace wp
