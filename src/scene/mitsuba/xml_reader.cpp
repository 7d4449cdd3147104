// Mitsuba 3's scene grammar read into plugin objects (xml_reader.hpp).
#include "scene/mitsuba/xml_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <deque>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>

#include <pugixml.hpp>

#include "scene/json_reader.hpp"
#include "scene/parse_number.hpp"
#include "util/file.hpp"
#include "util/one_line.hpp"

namespace wp::mitsuba {

std::string Location::text() const {
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

const char* value_tag(ValueKind kind) {
    switch (kind) {
    case ValueKind::Boolean:
        return "boolean";
    case ValueKind::Integer:
        return "integer";
    case ValueKind::Float:
        return "float";
    case ValueKind::String:
        return "string";
    case ValueKind::Point:
        return "point";
    case ValueKind::Vector:
        return "vector";
    case ValueKind::Rgb:
        return "rgb";
    case ValueKind::Spectrum:
        return "spectrum";
    case ValueKind::Transform:
        return "transform";
    }
    return "?";
}

namespace {

// An attribute value as a message quotes it: at most 40 bytes of it.
std::string clip(std::string_view value) {
    std::string s(value.substr(0, 40));
    if (value.size() > 40)
        s += "...";
    return s;
}

std::string element_text(const std::string& tag,
                         const std::vector<std::pair<std::string, std::string>>& attributes) {
    std::string s = "<" + tag;
    for (const auto& [key, value] : attributes)
        s += " " + key + "=\"" + clip(value) + "\"";
    return s + ">";
}

} // namespace

std::string Object::element() const {
    std::vector<std::pair<std::string, std::string>> attributes;
    if (!type.empty())
        attributes.emplace_back("type", type);
    if (!id.empty())
        attributes.emplace_back("id", id);
    return element_text(tag, attributes);
}

std::filesystem::path Object::folder() const {
    return std::filesystem::path(where.file).parent_path();
}

namespace {

std::filesystem::path resolve_in(const std::filesystem::path& folder, const std::string& name,
                                 const std::vector<std::filesystem::path>* search) {
    const std::filesystem::path own = folder / name;
    std::error_code ec;
    if (!search || std::filesystem::path(name).is_absolute() || std::filesystem::exists(own, ec))
        return own;
    for (const std::filesystem::path& other : *search)
        if (std::filesystem::exists(other / name, ec))
            return other / name;
    return own;
}

} // namespace

std::filesystem::path Object::resolve(const std::string& file_name) const {
    return resolve_in(folder(), file_name, search_folders.get());
}

void fail_at(const Location& where, const std::string& element, const std::string& problem) {
    throw SceneError(one_line(where.text() + ": " + element + ": " + problem));
}

namespace {

// One XML file, parsed, with what turns pugixml's byte offsets into lines
// and columns.
struct SourceFile {
    std::string name; // as messages print it
    std::string text;
    std::vector<std::size_t> line_starts{0};
    pugi::xml_document document;

    Location locate(std::ptrdiff_t offset) const {
        const auto at = static_cast<std::size_t>(std::max<std::ptrdiff_t>(offset, 0));
        const auto line = std::upper_bound(line_starts.begin(), line_starts.end(), at) - 1;
        return {name, static_cast<int>(line - line_starts.begin()) + 1,
                static_cast<int>(at - *line) + 1};
    }

    // An element's place: pugixml's offset is that of its name, one byte
    // after the '<' where messages point.
    Location at(const pugi::xml_node& node) const { return locate(node.offset_debug() - 1); }
};

// The tags of plugin objects (Mitsuba 3's object types).
const std::set<std::string, std::less<>> kObjectTags{"bsdf",   "emitter", "film",    "integrator",
                                                     "medium", "phase",   "rfilter", "sampler",
                                                     "sensor", "shape",   "texture", "volume"};

const std::array<std::pair<const char*, ValueKind>, 9> kValueTags{{
    {"boolean", ValueKind::Boolean},
    {"integer", ValueKind::Integer},
    {"float", ValueKind::Float},
    {"string", ValueKind::String},
    {"point", ValueKind::Point},
    {"vector", ValueKind::Vector},
    {"rgb", ValueKind::Rgb},
    {"spectrum", ValueKind::Spectrum},
    {"transform", ValueKind::Transform},
}};

// Numbers separated by commas and/or white space, as Mitsuba writes lists.
bool split_numbers(std::string_view text, std::vector<double>& out) {
    out.clear();
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && (text[i] == ',' || text[i] == ' ' || text[i] == '\t' ||
                                   text[i] == '\n' || text[i] == '\r'))
            ++i;
        if (i == text.size())
            break;
        std::size_t end = i;
        while (end < text.size() && text[end] != ',' && text[end] != ' ' && text[end] != '\t' &&
               text[end] != '\n' && text[end] != '\r')
            ++end;
        double value = 0.0;
        if (!parse_double(text.substr(i, end - i), value) || !std::isfinite(value))
            return false;
        out.push_back(value);
        i = end;
    }
    return true;
}

class Reader {
  public:
    explicit Reader(const std::map<std::string, std::string>& defines) : parameters_(defines) {}

    Document read(const std::filesystem::path& path) {
        const SourceFile& file = open(path, nullptr, "");
        const pugi::xml_node root = file.document.document_element();
        if (std::string_view(root.name()) != "scene")
            fail(file, root, "the root element must be <scene> (a Mitsuba scene file)");
        check_version(file, root);
        auto scene = std::make_shared<Object>();
        scene->tag = "scene";
        scene->where = file.at(root);
        scene->search_folders = search_folders_;
        read_contents(file, root, *scene);
        search_folders_->push_back(path.parent_path()); // last, after every <path>
        include_stack_.pop_back();
        resolve_forward_refs();
        return {scene, files_read_};
    }

  private:
    // A <ref> read before the element it names: Mitsuba 3 reads the whole
    // file before it builds anything, so a <ref> may come first (mitsuba-
    // data's cbox-rgb.xml includes shapes that refer to the area emitter it
    // declares after them).
    struct ForwardRef {
        Object* parent;
        std::size_t child; // its place in parent->children
        std::string id;
        Location where;
        std::string element;
    };

    void resolve_forward_refs() {
        for (const ForwardRef& ref : forward_refs_) {
            const auto it = ids_.find(ref.id);
            if (it == ids_.end())
                fail_at(ref.where, ref.element,
                        "refers to id '" + clip(ref.id) + "', which no element declares");
            // Only a forward <ref> can close a loop (an object inside itself).
            // Checked before the link is made, link by link, so that the loop
            // that would close is never made: a loop of shared pointers would
            // never be freed.
            if (contains(*it->second, ref.parent))
                fail_at(ref.where, ref.element,
                        "refers to id '" + clip(ref.id) +
                            "', which holds this <ref> itself: an object cannot contain itself");
            ref.parent->children[ref.child] = it->second;
        }
    }

    // Whether `target` is `from` or among its descendants (depth first, each
    // object visited once).
    static bool contains(const Object& from, const Object* target) {
        std::vector<const Object*> stack{&from};
        std::set<const Object*> seen;
        while (!stack.empty()) {
            const Object* o = stack.back();
            stack.pop_back();
            if (o == target)
                return true;
            if (!seen.insert(o).second)
                continue;
            for (const auto& child : o->children)
                stack.push_back(child.get());
        }
        return false;
    }

    // Reads and parses the file; `from` and `element` name the <include>
    // that asked for it, if any.
    const SourceFile& open(const std::filesystem::path& path, const Location* from,
                           const std::string& element) {
        std::error_code ec;
        std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
        if (ec)
            canonical = path;
        if (std::find(include_stack_.begin(), include_stack_.end(), canonical) !=
            include_stack_.end())
            fail_at(*from, element,
                    "include cycle: '" + path.string() +
                        "' is already being read (it includes "
                        "itself, directly or through other files)");
        SourceFile& file = files_.emplace_back();
        file.name = path.string();
        try {
            file.text = read_file_text(path);
        } catch (const FileError& e) {
            if (from)
                fail_at(*from, element, "cannot open '" + path.string() + "': " + e.reason());
            throw SceneError(one_line("cannot open scene '" + path.string() + "': " + e.reason()));
        }
        for (std::size_t i = 0; i < file.text.size(); ++i)
            if (file.text[i] == '\n')
                file.line_starts.push_back(i + 1);
        const pugi::xml_parse_result result = file.document.load_buffer(
            file.text.data(), file.text.size(), pugi::parse_default, pugi::encoding_utf8);
        if (!result)
            throw SceneError(one_line(file.locate(result.offset).text() +
                                      ": malformed XML: " + result.description()));
        include_stack_.push_back(canonical);
        files_read_.push_back(file.name);
        return file;
    }

    [[noreturn]] void fail(const SourceFile& file, const pugi::xml_node& node,
                           const std::string& problem) const {
        fail_at(file.at(node), describe(node), problem);
    }

    static std::string describe(const pugi::xml_node& node) {
        std::vector<std::pair<std::string, std::string>> attributes;
        for (const pugi::xml_attribute& a : node.attributes())
            if (attributes.size() < 2)
                attributes.emplace_back(a.name(), a.value());
        return element_text(node.name(), attributes);
    }

    // Mitsuba 3 reads files of format versions 2 and 3 as they are (it
    // upgrades older ones by renaming parameters, which wavepath does not).
    void check_version(const SourceFile& file, const pugi::xml_node& root) const {
        const pugi::xml_attribute version = root.attribute("version");
        if (!version)
            fail(file, root, "missing the format version (version=\"3.0.0\")");
        const std::string_view v = version.value();
        int major = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), major);
        if (ec != std::errc() || (end != v.data() + v.size() && *end != '.'))
            fail(file, root, "version '" + clip(v) + "' is not a version number such as 3.0.0");
        if (major < 2 || major > 3)
            fail(file, root,
                 "format version " + clip(v) +
                     ": wavepath reads Mitsuba scene files of versions 2.x and 3.x");
    }

    // An attribute's value with every $name replaced by its parameter's.
    std::string attribute(const SourceFile& file, const pugi::xml_node& node, const char* key,
                          bool required) const {
        const pugi::xml_attribute a = node.attribute(key);
        if (!a) {
            if (required)
                fail(file, node, std::string("missing the attribute '") + key + "'");
            return {};
        }
        const std::string_view raw = a.value();
        std::string out;
        for (std::size_t i = 0; i < raw.size(); ++i) {
            if (raw[i] != '$') {
                out += raw[i];
                continue;
            }
            std::size_t end = i + 1;
            while (end < raw.size() &&
                   (std::isalnum(static_cast<unsigned char>(raw[end])) || raw[end] == '_'))
                ++end;
            const std::string name(raw.substr(i + 1, end - i - 1));
            if (name.empty()) {
                out += '$';
                continue;
            }
            const auto it = parameters_.find(name);
            if (it == parameters_.end())
                fail(file, node,
                     "undefined parameter $" + clip(name) +
                         " (declare it first with <default "
                         "name=\"" +
                         clip(name) + "\" value=\"...\"/>)");
            out += it->second;
            i = end - 1;
        }
        return out;
    }

    // The children of `node` (a <scene> or a plugin object) into `object`.
    void read_contents(const SourceFile& file, const pugi::xml_node& node, Object& object) {
        std::set<std::string> names;
        for (const pugi::xml_node& child : node.children()) {
            if (child.type() != pugi::node_element)
                continue;
            const std::string_view tag = child.name();
            if (tag == "default") {
                const std::string name = attribute(file, child, "name", true);
                const std::string value = attribute(file, child, "value", true);
                parameters_.try_emplace(name, value); // an outside define wins
            } else if (tag == "include") {
                include(file, child, object);
            } else if (tag == "path") {
                add_search_folder(file, child);
            } else if (tag == "ref") {
                const std::string id = attribute(file, child, "id", true);
                const auto it = ids_.find(id);
                if (it == ids_.end()) // declared further on, perhaps: resolve_forward_refs
                    forward_refs_.push_back(
                        {&object, object.children.size(), id, file.at(child), describe(child)});
                object.children.push_back(it == ids_.end() ? nullptr : it->second);
                // A <ref> may name the parameter it fills: <ref id="grid" name="reflectance"/>.
                object.child_names.push_back(attribute(file, child, "name", false));
            } else if (kObjectTags.contains(tag) ||
                       (tag == "spectrum" && child.attribute("type"))) {
                object.children.push_back(read_object(file, child));
                object.child_names.push_back(object.children.back()->name);
            } else if (const auto kind = value_kind(tag)) {
                Parameter p = read_parameter(file, child, *kind);
                if (!names.insert(p.name).second)
                    fail(file, child, "parameter '" + clip(p.name) + "' is given twice");
                object.parameters.push_back(std::move(p));
            } else {
                fail(file, child,
                     "unknown element <" + clip(tag) +
                         "> (wavepath reads plugin objects (shape, bsdf, emitter, "
                         "sensor, film, sampler, rfilter, integrator), values "
                         "(boolean, integer, float, string, point, vector, rgb, "
                         "spectrum, transform), ref, default, include and path)");
            }
        }
    }

    static std::optional<ValueKind> value_kind(std::string_view tag) {
        for (const auto& [name, kind] : kValueTags)
            if (tag == name)
                return kind;
        return std::nullopt;
    }

    // <path value="../common"/>: a folder, relative to this file's, where
    // files that are not beside the file naming them are looked for (before
    // the main file's folder and the <path>s read earlier, as Mitsuba's
    // file resolver prepends it).
    void add_search_folder(const SourceFile& file, const pugi::xml_node& node) {
        const std::string value = attribute(file, node, "value", true);
        const std::filesystem::path folder = std::filesystem::path(file.name).parent_path() / value;
        std::error_code ec;
        if (!std::filesystem::is_directory(folder, ec))
            fail(file, node, "the folder '" + folder.string() + "' does not exist");
        search_folders_->insert(search_folders_->begin(), folder);
    }

    void include(const SourceFile& file, const pugi::xml_node& node, Object& object) {
        const std::string name = attribute(file, node, "filename", true);
        const std::filesystem::path path =
            resolve_in(std::filesystem::path(file.name).parent_path(), name, search_folders_.get());
        const Location where = file.at(node);
        const SourceFile& included = open(path, &where, describe(node));
        const pugi::xml_node root = included.document.document_element();
        if (std::string_view(root.name()) != "scene")
            fail(included, root, "an included file's root element must be <scene>");
        check_version(included, root);
        read_contents(included, root, object);
        include_stack_.pop_back();
    }

    // Objects nested deeper than this are refused: a real scene nests a few
    // levels (a twosided BSDF in a shape in a scene), and a hostile file of
    // 10^5 nested elements overflowed the stack (reading, and destroying the
    // chain of objects) before this limit.
    static constexpr int kMaxNesting = 64;

    std::shared_ptr<const Object> read_object(const SourceFile& file, const pugi::xml_node& node) {
        if (nesting_ >= kMaxNesting)
            fail(file, node, "objects nested more than " + std::to_string(kMaxNesting) + " deep");
        ++nesting_;
        struct Leave {
            int& depth;
            ~Leave() { --depth; }
        } leave{nesting_};
        auto object = std::make_shared<Object>();
        object->tag = node.name();
        object->where = file.at(node);
        object->type = attribute(file, node, "type", true);
        object->id = attribute(file, node, "id", false);
        object->name = attribute(file, node, "name", false);
        object->search_folders = search_folders_;
        read_contents(file, node, *object);
        if (!object->id.empty() && !ids_.emplace(object->id, object).second)
            fail(file, node, "id '" + clip(object->id) + "' is already declared");
        return object;
    }

    // x, y and z attributes (each `missing` when absent), or a `value` of
    // three numbers or of one for all three.
    glm::dvec3 xyz(const SourceFile& file, const pugi::xml_node& node, double missing,
                   const char* key = "value") const {
        const bool has_value = static_cast<bool>(node.attribute(key));
        const bool has_xyz = node.attribute("x") || node.attribute("y") || node.attribute("z");
        if (has_value && has_xyz)
            fail(file, node, std::string("give either '") + key + "' or x, y and z, not both");
        if (has_value)
            return triple(file, node, key);
        glm::dvec3 v(missing);
        const char* axes[3] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i)
            if (node.attribute(axes[i]))
                v[i] = single(file, node, axes[i]);
        return v;
    }

    double single(const SourceFile& file, const pugi::xml_node& node, const char* key) const {
        const std::string text = attribute(file, node, key, true);
        std::vector<double> values;
        if (!split_numbers(text, values) || values.size() != 1)
            fail(file, node,
                 std::string("attribute '") + key + "': expected a number, got '" + clip(text) +
                     "'");
        return values[0];
    }

    // Three numbers, or one standing for all three (Mitsuba's shorthand).
    glm::dvec3 triple(const SourceFile& file, const pugi::xml_node& node, const char* key) const {
        const std::string text = attribute(file, node, key, true);
        std::vector<double> values;
        if (!split_numbers(text, values) || (values.size() != 1 && values.size() != 3))
            fail(file, node,
                 std::string("attribute '") + key +
                     "': expected 3 numbers (or 1 for all three), got '" + clip(text) + "'");
        return values.size() == 1 ? glm::dvec3(values[0])
                                  : glm::dvec3(values[0], values[1], values[2]);
    }

    Parameter read_parameter(const SourceFile& file, const pugi::xml_node& node, ValueKind kind) {
        Parameter p;
        p.kind = kind;
        p.where = file.at(node);
        p.name = attribute(file, node, "name", true);
        p.element = element_text(node.name(), {{"name", p.name}});
        switch (kind) {
        case ValueKind::Boolean: {
            const std::string v = attribute(file, node, "value", true);
            if (v != "true" && v != "false")
                fail(file, node, "expected true or false, got '" + clip(v) + "'");
            p.boolean = v == "true";
            break;
        }
        case ValueKind::Integer: {
            const std::string v = attribute(file, node, "value", true);
            const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), p.integer);
            if (ec != std::errc() || end != v.data() + v.size())
                fail(file, node, "expected an integer, got '" + clip(v) + "'");
            break;
        }
        case ValueKind::Float:
            p.number = single(file, node, "value");
            break;
        case ValueKind::String:
            p.text = attribute(file, node, "value", true);
            break;
        case ValueKind::Point:
        case ValueKind::Vector:
            p.vector = xyz(file, node, 0.0);
            break;
        case ValueKind::Rgb:
            p.vector = triple(file, node, "value");
            break;
        case ValueKind::Spectrum: {
            if (node.attribute("filename"))
                fail(file, node,
                     "spectra from files are not supported (give a single value, "
                     "or use <rgb>)");
            const std::string v = attribute(file, node, "value", true);
            if (v.find(':') != std::string::npos) {
                read_spectrum_pairs(file, node, v, p);
                break;
            }
            std::vector<double> values;
            if (!split_numbers(v, values) || values.size() != 1)
                fail(file, node,
                     "expected a single value or wavelength:value pairs, got '" + clip(v) + "'");
            p.number = values[0];
            p.vector = glm::dvec3(values[0]);
            break;
        }
        case ValueKind::Transform:
            p.transform = read_transform(file, node);
            break;
        }
        return p;
    }

    // "400:0.5, 500:0.7, ...": at least two pairs, wavelengths increasing,
    // every number finite (as Mitsuba's Properties::Spectrum demands).
    void read_spectrum_pairs(const SourceFile& file, const pugi::xml_node& node,
                             const std::string& text, Parameter& p) const {
        std::vector<double> numbers;
        std::string flat = text;
        std::replace(flat.begin(), flat.end(), ':', ' ');
        std::size_t colons = static_cast<std::size_t>(std::count(text.begin(), text.end(), ':'));
        if (!split_numbers(flat, numbers) || numbers.size() != 2 * colons || colons < 2)
            fail(file, node,
                 "expected wavelength:value pairs (at least two, such as \"400:0.5, "
                 "700:0.8\"), got '" +
                     clip(text) + "'");
        for (std::size_t i = 0; i < colons; ++i) {
            p.wavelengths.push_back(numbers[2 * i]);
            p.values.push_back(numbers[2 * i + 1]);
            if (i > 0 && !(p.wavelengths[i] > p.wavelengths[i - 1]))
                fail(file, node,
                     "the wavelengths must increase, but " + json::number_text(p.wavelengths[i]) +
                         " follows " + json::number_text(p.wavelengths[i - 1]));
        }
    }

    // The steps of a <transform>, applied in the order they are written:
    // each acts on what the ones before it made (Mitsuba's order, and
    // Transform::compose's).
    wp::Transform read_transform(const SourceFile& file, const pugi::xml_node& node) const {
        wp::Transform t;
        for (const pugi::xml_node& step : node.children()) {
            if (step.type() != pugi::node_element)
                continue;
            const std::string_view tag = step.name();
            try {
                if (tag == "translate") {
                    t = t.then(wp::Transform::translate(xyz(file, step, 0.0)));
                } else if (tag == "scale") {
                    t = t.then(wp::Transform::scale(xyz(file, step, 1.0)));
                } else if (tag == "rotate") {
                    const double angle = single(file, step, "angle");
                    t = t.then(wp::Transform::rotate(angle, xyz(file, step, 0.0)));
                } else if (tag == "matrix") {
                    t = t.then(matrix(file, step));
                } else if (tag == "lookat") {
                    if (!step.attribute("up"))
                        fail(file, step, "missing the attribute 'up'");
                    t = t.then(wp::Transform::look_at(triple(file, step, "origin"),
                                                      triple(file, step, "target"),
                                                      triple(file, step, "up")));
                } else {
                    fail(file, step,
                         "unknown transform step (expected translate, rotate, scale, "
                         "matrix or lookat)");
                }
            } catch (const TransformError& e) {
                fail(file, step, e.what());
            }
        }
        return t;
    }

    // 16 numbers row by row, or 9 for the linear part alone.
    wp::Transform matrix(const SourceFile& file, const pugi::xml_node& node) const {
        const std::string text = attribute(file, node, "value", true);
        std::vector<double> v;
        if (!split_numbers(text, v) || (v.size() != 16 && v.size() != 9))
            fail(file, node,
                 "expected 16 numbers (a 4x4 matrix row by row) or 9 (3x3), got '" + clip(text) +
                     "'");
        std::array<double, 16> rows{};
        if (v.size() == 16) {
            std::copy(v.begin(), v.end(), rows.begin());
        } else {
            for (std::size_t r = 0; r < 3; ++r)
                for (std::size_t c = 0; c < 3; ++c)
                    rows[r * 4 + c] = v[r * 3 + c];
            rows[15] = 1.0;
        }
        return wp::Transform::from_rows(rows);
    }

    std::map<std::string, std::string> parameters_;
    std::map<std::string, std::shared_ptr<const Object>, std::less<>> ids_;
    std::vector<std::filesystem::path> include_stack_;
    std::vector<ForwardRef> forward_refs_;
    std::shared_ptr<std::vector<std::filesystem::path>> search_folders_ =
        std::make_shared<std::vector<std::filesystem::path>>();
    int nesting_ = 0;              // read_object's depth
    std::deque<SourceFile> files_; // stable addresses: Locations are made as files are read
    std::vector<std::string> files_read_;
};

} // namespace

Document read_document(const std::filesystem::path& path,
                       const std::map<std::string, std::string>& defines) {
    return Reader(defines).read(path);
}

} // namespace wp::mitsuba
