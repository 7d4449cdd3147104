#include "app/view_cli.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "app/cli_options.hpp"
#include "image/exposure.hpp"

namespace wp {

void add_view_options(CLI::App& command, ViewOptions& view) {
    command
        .add_option_function<std::string>(
            "--tonemap",
            [&view](const std::string& name) {
                view.tonemap = name == "seed"     ? ToneMap::Seed
                               : name == "filmic" ? ToneMap::Filmic
                                                  : ToneMap::Srgb;
            },
            "PNG view: 'srgb' (exposure, then the sRGB curve; values past white clip), "
            "'filmic' (exposure, then ACES's curve in Hill's fit: highlights roll off) or "
            "'seed' (the report's: sqrt, divided by the image maximum, times 255.99)")
        ->default_str("srgb")
        ->check(CLI::IsMember({"srgb", "filmic", "seed"}));
    CLI::Option* offset =
        command
            .add_option("--exposure", view.exposure_stops,
                        "PNG exposure in stops from the automatic one, which maps the median "
                        "luminance to mid grey and clips at most 1 % of the pixels, leaving "
                        "out the lights (srgb and filmic views)")
            ->capture_default_str()
            ->check(finite_number);
    command
        .add_option_function<double>(
            "--fixed-exposure",
            [&view](double stops) {
                view.exposure = Exposure::Fixed;
                view.exposure_stops = stops;
            },
            "PNG exposure in stops, not adapted to the image: linear values times 2^STOPS "
            "(for views that compare renders)")
        ->check(finite_number)
        ->excludes(offset);
}

double emitter_luminance_threshold(const Scene& scene) {
    // Without an emitting material no triangle needs looking at.
    if (std::none_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
            return luminance(m.emission.x, m.emission.y, m.emission.z) > 0.0;
        }))
        return std::numeric_limits<double>::infinity();
    std::vector<bool> used(scene.materials.size(), false);
    for (const Triangle& t : scene.triangles)
        used[t.material] = true;
    double dimmest = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const glm::dvec3 e = scene.materials[m].emission;
        const double y = luminance(e.x, e.y, e.z);
        if (used[m] && y > 0.0)
            dimmest = std::min(dimmest, y);
    }
    return 0.5 * dimmest;
}

ViewOptions view_for_scene(ViewOptions view, const Scene& scene) {
    view.emitter_luminance = emitter_luminance_threshold(scene);
    return view;
}

} // namespace wp
