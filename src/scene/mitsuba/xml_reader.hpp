// Mitsuba 3's scene grammar (docs/mitsuba-import.md), read with pugixml into
// a tree of plugin objects whose parameters are typed values, each with the
// place in the file it came from. What the grammar itself settles is done
// here: `<include>` (with cycles refused), `<default>` and `$name`
// substitution, `id` and `<ref>`, the value tags (`<float>`, `<rgb>`,
// `<transform>`, ...). What a plugin makes of its parameters is the plugin
// readers' job (sensor.hpp, bsdfs.hpp, shapes.hpp), and nothing here knows
// wavepath's Scene.
//
// Every problem is one SceneError whose message starts with the place:
//   "box.xml:12:9: <float name="fov">: expected a number, got 'wide'"
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/scene.hpp"
#include "scene/transform.hpp"

namespace wp::mitsuba {

// Where an element starts: its file (as the scene named it), line and
// column, both from 1.
struct Location {
    std::string file;
    int line = 0;
    int column = 0;

    // "box.xml:12:9"
    std::string text() const;
};

// The kinds of value a parameter can hold, one per value tag.
enum class ValueKind { Boolean, Integer, Float, String, Point, Vector, Rgb, Spectrum, Transform };

// The tag that holds a kind ("float", "rgb", ...).
const char* value_tag(ValueKind kind);

// One named parameter of a plugin: `<float name="fov" value="45"/>`.
struct Parameter {
    std::string name;
    ValueKind kind = ValueKind::Float;
    Location where;
    std::string element; // the element as messages quote it: <float name="fov">
    bool boolean = false;
    long long integer = 0;
    double number = 0.0; // Float, and a Spectrum of a single value
    // A Spectrum of wavelength:value pairs (wavelengths in nm, increasing);
    // empty for a single value. Parameters::color turns it into RGB.
    std::vector<double> wavelengths, values;
    std::string text;        // String
    glm::dvec3 vector{0.0};  // Point, Vector, Rgb
    wp::Transform transform; // Transform
};

// One plugin instance: `<bsdf type="diffuse" id="white">` with its
// parameters and the objects nested in it or referred to by `<ref>` (the
// same object, shared, however often it is referred to).
struct Object {
    std::string tag;  // "shape", "bsdf", "sensor", ...
    std::string type; // the plugin: "diffuse", "obj", ...
    std::string id;   // empty when it has none
    std::string name; // the name it is nested under (`name="..."`), if any
    Location where;
    std::vector<Parameter> parameters;
    std::vector<std::shared_ptr<const Object>> children;
    // The name each child fills here (children[i]'s own `name`, or that of
    // the <ref> that brought it), empty when none.
    std::vector<std::string> child_names;

    // How messages quote it: <bsdf type="diffuse" id="white">
    std::string element() const;
    // The folder relative paths in this object resolve against first: its file's.
    std::filesystem::path folder() const;
    // Where a file this object names is, as Mitsuba's file resolver finds
    // it: relative to folder(), else to each folder the scene's <path>
    // elements add (the last first), else to the main scene file's folder;
    // the first that exists. When none does, folder() / name, for the
    // message of whoever opens it.
    std::filesystem::path resolve(const std::string& file_name) const;
    // The <path> folders and the main file's, in search order (shared by
    // every object of a document).
    std::shared_ptr<const std::vector<std::filesystem::path>> search_folders;
};

struct Document {
    std::shared_ptr<const Object> scene; // the <scene> root, includes merged in
    std::vector<std::string> files;      // every XML file read, the scene's first
};

// `defines` are the values of `$name` given from outside (Mitsuba's -D):
// they win over the file's `<default>`s. Throws SceneError.
Document read_document(const std::filesystem::path& path,
                       const std::map<std::string, std::string>& defines = {});

// The message of a problem at `where` with `element`: "<where>: <element>: <problem>".
[[noreturn]] void fail_at(const Location& where, const std::string& element,
                          const std::string& problem);

} // namespace wp::mitsuba
