// A Mitsuba 3 scene file as a wavepath Scene (docs/mitsuba-import.md): the
// grammar (xml_reader.hpp), then each plugin by its family: the sensor
// (sensor.hpp), the BSDFs (bsdfs.hpp), the shapes (shapes.hpp), the area
// emitters and the integrator (here). load_scene (scene/load.hpp) comes
// here for files ending in .xml.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "scene/scene.hpp"
#include "scene/scene_read_options.hpp"

namespace wp {

// Throws SceneError: one line naming the file, the line and column, the
// element, and what wavepath supports there. `options.defines` set
// `$name`s as Mitsuba's -D does (they win over the file's <default>s);
// `options.lenient` turns the refusals docs/mitsuba-import.md lists under
// "--lenient" into warnings in Scene::warnings, one per element.
Scene load_mitsuba_scene(const std::filesystem::path& path, const SceneReadOptions& options = {});

} // namespace wp
