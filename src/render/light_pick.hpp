// How next-event estimation chooses an emissive triangle: by area, or by the
// power it emits (its area times the luminance of its radiance), which sends
// the samples where the light is (docs/lights-and-camera.md, "Choosing a
// light"). Where every emissive triangle has one luminance the two are the
// same choice, and such a scene (the hexroom) keeps the area pick's code and
// bits: the power pick is a feature switch of its own,
// WP_HAS_POWER_LIGHT_PICK (kernels/scene_features.h), on only where the
// luminances differ.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "render/device_array.hpp"
#include "wp_shared.h"

namespace wp {

struct Scene;

enum class LightPick {
    Power, // by power where the emissive triangles' luminances differ (else by area: the same)
    Area,  // by area always (--light-pick area: the images of before the power pick)
};
std::string to_string(LightPick pick); // "power", "area"

// Whether the scene's emissive triangles differ in luminance, so that picking
// them by power differs from picking them by area.
bool triangle_radiances_differ(const Scene& scene);

// The light table for the emissive triangles `lights` (their triangle numbers
// set) of areas `areas` (in the float frame): each one's cdf, by area or, with
// `by_power`, by area times luminance, and its guide (set_light_guides); and in
// each emissive material's emission.w the area over which the pick spreads
// its triangles' probability, total weight / (weight / area): the kernels'
// wp_light_area (kernels/lights.h), 1 / the pick's density per unit area.
// By area that is the total area, for every material, exactly the float
// WpFrame.light_area holds, so the general kernels (which read emission.w)
// render the area pick's bits.
void build_light_pick(const Scene& scene, const std::vector<double>& areas, bool by_power,
                      DeviceArray<WpLight>& lights, DeviceArray<WpMaterial>& materials);

} // namespace wp
