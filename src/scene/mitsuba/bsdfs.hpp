// Mitsuba 3's BSDF plugins as wavepath materials: diffuse, conductor,
// roughconductor, dielectric, thindielectric, plastic, and twosided around
// any of the ones that only reflect. Parameters and defaults are Mitsuba's
// (docs/materials.md says how wavepath computes each).
#pragma once

#include <string>
#include <vector>

#include "scene/mitsuba/textures.hpp"
#include "scene/mitsuba/xml_reader.hpp"
#include "scene/scene.hpp"

namespace wp::mitsuba {

// The material of `bsdf` (with no emission; Material::name is left empty).
// wavepath's reflecting materials reflect alike on both sides; Mitsuba's do
// only inside `twosided`, so a bare one that reflects anything adds a line
// to `warnings`. Throws SceneError.
// Textures the BSDF uses go to `textures` (the material names them by number).
Material read_bsdf(const Object& bsdf, TextureTable& textures, std::vector<std::string>& warnings);

} // namespace wp::mitsuba
