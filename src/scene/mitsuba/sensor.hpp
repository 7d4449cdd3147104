// Mitsuba 3's sensors as wavepath's camera: `perspective` and `thinlens`
// with their `hdrfilm` (size and pixel filter) and sampler.
#pragma once

#include <string>
#include <vector>

#include "scene/mitsuba/xml_reader.hpp"
#include "scene/scene.hpp"

namespace wp::mitsuba {

// The camera of `sensor`. Mitsuba's camera looks along +z of its to_world
// frame with +y up in the image and +x to the image's left (docs/mitsuba-
// export.md writes the inverse), so to_world must be a rotation, a uniform
// scale and a translation: a mirror would flip the image, which wavepath's
// camera cannot. Throws SceneError.
Camera read_sensor(const Object& sensor, std::vector<std::string>& warnings);

} // namespace wp::mitsuba
