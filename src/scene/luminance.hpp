// The luminance of a linear RGB colour, for the host's choices that weigh
// colours by brightness: which emissive triangle to sample (light_pick), how
// an environment map's pixels are sampled (environment_tables), and a colour
// texture read as a float parameter such as a roughness (Texture::eval_float).
//
// The weights are the Y row of the sRGB (Rec. 709) primaries to CIE XYZ matrix
// as Mitsuba 3 writes them (its `luminance()`, mitsuba/core/spectrum.h), so that
// a scene imported from Mitsuba picks its lights and reads its textures as
// Mitsuba does; the kernels' texture reads use the same three numbers
// (kernels/textures/texture.h). The display's exposure (image/exposure) keeps
// the rounded Rec. 709 weights: it measures pixels, it does not sample.
#pragma once

#include <glm/vec3.hpp>

namespace wp {

inline double luminance(const glm::dvec3& c) {
    return 0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z;
}

} // namespace wp
