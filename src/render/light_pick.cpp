#include "render/light_pick.hpp"

#include <optional>

#include "render/device_scene.hpp"
#include "scene/luminance.hpp"
#include "scene/scene.hpp"

namespace wp {

std::string to_string(LightPick pick) {
    switch (pick) {
    case LightPick::Power:
        return "power";
    case LightPick::Area:
        return "area";
    }
    return "?";
}

bool triangle_radiances_differ(const Scene& scene) {
    // Only emissive materials of two luminances can differ: otherwise no
    // pass over a big mesh's triangles.
    std::optional<double> some;
    bool two = false;
    for (const Material& material : scene.materials)
        if (material.is_emissive()) {
            const double y = luminance(material.emission);
            two = two || (some && *some != y);
            some = y;
        }
    if (!two)
        return false;
    bool found = false;
    double first = 0.0;
    for (const Triangle& t : scene.triangles) {
        const Material& material = scene.materials[t.material];
        if (!material.is_emissive())
            continue;
        const double y = luminance(material.emission);
        if (found && y != first)
            return true;
        found = true;
        first = y;
    }
    return false;
}

void build_light_pick(const Scene& scene, const std::vector<double>& areas, bool by_power,
                      DeviceArray<WpLight>& lights, DeviceArray<WpMaterial>& materials) {
    auto material_of = [&](const WpLight& light) {
        return scene.triangles[light.triangle].material;
    };
    std::vector<double> weights(areas);
    if (by_power)
        for (std::size_t i = 0; i < lights.size(); ++i)
            weights[i] *= luminance(scene.materials[material_of(lights[i])].emission);
    double total = 0.0;
    for (double w : weights)
        total += w;
    double running = 0.0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        running += weights[i];
        lights[i].cdf = static_cast<float>(running / total);
    }
    if (!lights.empty())
        lights.back().cdf = 1.0f; // never let rounding leave u in no bin
    set_light_guides(lights);
    // A triangle's density per unit area is its weight / total over its area,
    // (weight / area) being the material's luminance (by power) or 1 (by area).
    for (const WpLight& light : lights) {
        const std::uint32_t m = material_of(light);
        const double per_area = by_power ? luminance(scene.materials[m].emission) : 1.0;
        materials[m].emission.s[3] = static_cast<float>(total / per_area);
    }
}

} // namespace wp
