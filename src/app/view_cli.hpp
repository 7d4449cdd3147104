// The PNG view's command-line options (--tonemap, --exposure,
// --fixed-exposure), shared by every command that writes a view of a render,
// and what the view learns from the scene.
#pragma once

#include "image/tonemap.hpp"
#include "scene/scene.hpp"

#include <CLI/CLI.hpp>

namespace wp {

void add_view_options(CLI::App& command, ViewOptions& view);

// A pixel at half the luminance of the scene's dimmest emitter or more sees
// an emitter (directly, or in a mirror of reflectance 1/2 or more) over at
// least half its area, or an emitter brighter than the dimmest. A diffuse
// surface reaches it only when an emitter fills most of its hemisphere
// (its radiance is at most its albedo times the emitters' radiance). Infinity
// (nothing left out) for a scene without emitters.
double emitter_luminance_threshold(const Scene& scene);

// view with emitter_luminance set from the scene.
ViewOptions view_for_scene(ViewOptions view, const Scene& scene);

} // namespace wp
