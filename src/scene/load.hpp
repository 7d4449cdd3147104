// Reading a scene description (JSON, format in docs/scene-format.md) into a
// validated wp::Scene. Every problem is reported as one SceneError whose
// message names the source and the offending field as a JSON pointer, e.g.
//   "hexroom.json: /shapes/3/radius: must be positive, got -1".
// Zero-area triangles are not errors: they are skipped and listed in
// Scene::warnings ("/shapes/7: skipped zero-area triangle").
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "scene/scene.hpp"
#include "scene/scene_read_options.hpp"

namespace wp {

// Reads and parses the file: a Mitsuba 3 scene when its name ends in .xml
// (any case; scene/mitsuba/load_mitsuba.hpp, docs/mitsuba-import.md), else
// wavepath's JSON. Throws SceneError("cannot open scene '<path>': <reason>")
// when the file cannot be opened or read, and whatever parse_scene throws otherwise.
// Scene::source is the path as given.
Scene load_scene(const std::filesystem::path& path);

// The same with values for a Mitsuba scene's `$name`s, as Mitsuba's -D gives
// them (they win over the file's <default>s). A JSON scene has no `$name`s:
// defines given for one are a SceneError that says so.
Scene load_scene(const std::filesystem::path& path,
                 const std::map<std::string, std::string>& defines);

// The same with -D's defines and --lenient (scene_read_options.hpp); a JSON
// scene refuses either, as it has no `$name`s and is read strictly.
Scene load_scene(const std::filesystem::path& path, const SceneReadOptions& options);

// Parses and validates a scene from JSON text. source_name is used in messages
// and stored in Scene::source; mesh files named by the scene are found relative
// to its folder (the working directory when it has none, e.g. "test.json").
// Syntax errors are reported with the parser's byte position, the line and
// column, and the JSON pointer of the value being read.
Scene parse_scene(std::string_view json_text, const std::string& source_name);

} // namespace wp
