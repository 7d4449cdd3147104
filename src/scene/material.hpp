// The material table on the host: kind names, named metals, and the
// parameters each kind reads from a scene file.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.hpp"

namespace wp {

// The kind named `name` in a scene file ("diffuse", "roughconductor", ...).
std::optional<MaterialKind> material_kind_from_name(std::string_view name);

// Every kind's name, comma-separated, for messages.
std::string material_kind_names();

// A conductor's complex index of refraction, per RGB channel.
struct NamedMetal {
    const char* name; // Mitsuba's name: "Au", "Ag", ...
    glm::dvec3 eta;
    glm::dvec3 k;
};

// The named metals wavepath knows, and the one of that name (nullptr when none).
const std::vector<NamedMetal>& named_metals();
const NamedMetal* find_metal(std::string_view name);

// A dielectric's index of refraction by Mitsuba's name ("bk7", "water", ...).
struct NamedIor {
    const char* name;
    double ior;
};

// The diffuse Fresnel reflectance of a dielectric interface of relative
// index eta: the share of light arriving uniformly over the hemisphere (by
// cosine) that the interface reflects. Mitsuba 3's fits (render/fresnel.h):
// Egan and Hilgeman (1973) below 1, d'Eon and Irving (2011) above.
double fresnel_diffuse_reflectance(double eta);

// A roughplastic's rough coating, integrated over its microfacets as Mitsuba
// 3's roughplastic integrates it (its parameters_changed(), with
// eval_transmittance and eval_reflectance of render/microfacet.h): the
// transmittance from outside at incidence cosines max(1e-6, i / (RES - 1))
// (RES = WP_ROUGH_TRANSMITTANCE_RES), and the hemispherical reflectance seen
// from inside. Isotropic roughness alpha > 0, eta = int_ior / ext_ior > 0.
struct RoughCoating {
    std::vector<double> transmittance; // RES values
    double internal_reflectance = 0.0;
};
RoughCoating rough_coating(MicrofacetDistribution distribution, double alpha, double eta);

// The named indices of refraction, and the one of that name (nullptr when none).
const std::vector<NamedIor>& named_iors();
const NamedIor* find_ior(std::string_view name);

} // namespace wp
