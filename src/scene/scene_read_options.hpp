// How load_scene reads a scene beyond its file: the values of a Mitsuba
// scene's `$name`s from the command line (-D), and --lenient, which renders
// a Mitsuba scene with what wavepath cannot read replaced or left out
// (docs/mitsuba-import.md, "--lenient"). Neither means anything to a JSON
// scene, and load_scene refuses both for one.
#pragma once

#include <map>
#include <string>

namespace wp {

struct SceneReadOptions {
    // `$name` values that win over the file's <default>s, as Mitsuba's -D.
    std::map<std::string, std::string> defines;
    // Replace a BSDF wavepath cannot read by a grey diffuse, and leave out a
    // shape, an emitter or an integrator of a plugin it does not have, each
    // with a warning, instead of refusing the scene.
    bool lenient = false;
};

} // namespace wp
