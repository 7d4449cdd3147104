#include "scene/load.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scene/validate.hpp"
#include "util/file.hpp"

namespace wp {

namespace {

// ordered_json keeps the file's order, so materials get indices in file order.
using Json = nlohmann::ordered_json;

std::string fmt(double x) {
    std::array<char, 64> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
    return std::string(buf.data(), res.ptr);
}

// A computed value, to 4 significant digits.
std::string fmt4(double x) {
    std::array<char, 64> buf{};
    const auto res =
        std::to_chars(buf.data(), buf.data() + buf.size(), x, std::chars_format::general, 4);
    return std::string(buf.data(), res.ptr);
}

// Messages are one line: control characters (from keys or names) become '?'.
std::string one_line(std::string s) {
    for (char& ch : s)
        if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
            ch = '?';
    return s;
}

// A string shortened to at most n bytes, without cutting a UTF-8 sequence.
std::string shorten(const std::string& s, std::size_t n) {
    if (s.size() <= n)
        return s;
    std::size_t cut = n;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80)
        --cut;
    return s.substr(0, cut) + "...";
}

// A JSON pointer (RFC 6901) to a value in the document.
class Ptr {
  public:
    Ptr() = default;
    Ptr operator/(std::string_view key) const {
        Ptr p = *this;
        p.s_ += '/';
        for (char ch : key) {
            if (ch == '~')
                p.s_ += "~0";
            else if (ch == '/')
                p.s_ += "~1";
            else
                p.s_ += ch;
        }
        return p;
    }
    Ptr operator/(std::size_t index) const {
        Ptr p = *this;
        p.s_ += '/';
        p.s_ += std::to_string(index);
        return p;
    }
    // The root's pointer is the empty string; messages name it "(root)".
    std::string str() const { return s_.empty() ? std::string("(root)") : s_; }

  private:
    std::string s_;
};

// A short description of a value for "expected X, got Y" messages.
std::string describe(const Json& v) {
    switch (v.type()) {
    case Json::value_t::null:
        return "null";
    case Json::value_t::boolean:
        return v.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
        return v.dump();
    case Json::value_t::number_float:
        return fmt(v.get<double>());
    case Json::value_t::string:
        return "\"" + shorten(v.get_ref<const std::string&>(), 40) + "\"";
    case Json::value_t::array:
        return "an array of " + std::to_string(v.size()) +
               (v.size() == 1 ? " element" : " elements");
    case Json::value_t::object:
        return "an object";
    default:
        return "a value of type " + std::string(v.type_name());
    }
}

// ---------------------------------------------------------------------------
// JSON text -> DOM, through a SAX handler so that every error (syntax, number
// overflow, duplicate key) comes with the JSON pointer of the value being read
// and, where the parser knows it, the byte position.

class DomBuilder final : public nlohmann::json_sax<Json> {
  public:
    Json root;

    bool failed = false;
    bool has_position = false;
    std::size_t position = 0; // nlohmann's count of bytes read, the failing one included
    std::string pointer;      // where it failed
    std::string problem;

    bool null() override { return put(Json(nullptr)); }
    bool boolean(bool val) override { return put(Json(val)); }
    bool number_integer(number_integer_t val) override { return put(Json(val)); }
    bool number_unsigned(number_unsigned_t val) override { return put(Json(val)); }
    bool number_float(number_float_t val, const string_t& /*text*/) override {
        return put(Json(val));
    }
    bool string(string_t& val) override { return put(Json(std::move(val))); }
    bool binary(binary_t& /*val*/) override { return put(Json(nullptr)); } // not in JSON text

    bool start_object(std::size_t /*elements*/) override {
        Json* v = place(Json::object());
        frames_.push_back(Frame{v, false, 0, {}, {}});
        return true;
    }
    bool key(string_t& val) override {
        Frame& f = frames_.back();
        if (!f.keys.insert(val).second) {
            failed = true;
            pointer = (path(frames_.size() - 1) / std::string_view(val)).str();
            problem = "duplicate key '" + shorten(val, 60) +
                      "' (the later value would silently replace the earlier one)";
            return false;
        }
        f.key = val;
        pending_ = &(*f.value)[val];
        return true;
    }
    bool end_object() override {
        frames_.pop_back();
        return true;
    }
    bool start_array(std::size_t /*elements*/) override {
        Json* v = place(Json::array());
        frames_.push_back(Frame{v, true, 0, {}, {}});
        return true;
    }
    bool end_array() override {
        frames_.pop_back();
        return true;
    }
    bool parse_error(std::size_t pos, const std::string& last_token,
                     const nlohmann::detail::exception& ex) override {
        failed = true;
        has_position = true;
        position = pos;
        pointer = error_path().str();
        if (ex.id == 406) { // out_of_range.406: number overflow, e.g. 1e999
            problem =
                "number " + shorten(last_token, 40) + " is out of range (it overflows to infinity)";
        } else {
            std::string what = ex.what();
            // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax error..."
            if (const auto close = what.find("] ");
                !what.empty() && what[0] == '[' && close != std::string::npos)
                what.erase(0, close + 2);
            if (what.rfind("parse error", 0) == 0)
                if (const auto colon = what.find(": "); colon != std::string::npos)
                    what.erase(0, colon + 2);
            problem = "invalid JSON: " + what;
        }
        return false;
    }

  private:
    struct Frame {
        Json* value;
        bool is_array;
        std::size_t count; // elements placed so far (arrays)
        std::string key;   // the member being read (objects)
        std::unordered_set<std::string> keys;
    };

    // Pointer to the value being read inside the first n frames.
    Ptr path(std::size_t n) const {
        Ptr p;
        for (std::size_t i = 0; i < n; ++i) {
            const Frame& f = frames_[i];
            p = f.is_array ? p / (f.count == 0 ? 0 : f.count - 1) : p / f.key;
        }
        return p;
    }

    // Where a parse error happened: inside an array, the element after the
    // last one that was placed.
    Ptr error_path() const {
        if (frames_.empty())
            return Ptr();
        const Frame& top = frames_.back();
        Ptr p = path(frames_.size() - 1);
        if (top.is_array)
            return p / top.count;
        return top.key.empty() ? p : p / top.key;
    }

    Json* place(Json&& v) {
        if (frames_.empty()) {
            root = std::move(v);
            return &root;
        }
        Frame& f = frames_.back();
        if (f.is_array) {
            f.value->push_back(std::move(v));
            ++f.count;
            return &f.value->back();
        }
        *pending_ = std::move(v);
        return pending_;
    }
    bool put(Json&& v) {
        place(std::move(v));
        return true;
    }

    std::vector<Frame> frames_;
    Json* pending_ = nullptr; // the object member whose value comes next
};

// ---------------------------------------------------------------------------
// DOM -> Scene, validating every field.

enum class Range { Coordinate, Reflectance, Radiance };

class SceneReader {
  public:
    explicit SceneReader(const std::string& source) { scene_.source = source; }

    Scene read(const Json& root) {
        const Ptr top;
        expect_object(root, top, "a scene object with camera, materials and shapes");
        check_keys(root, top, {"camera", "materials", "shapes", "description"});
        if (const auto it = root.find("description"); it != root.end())
            expect_string(*it, top / "description");
        read_camera(require(root, top, "camera"), top / "camera");
        read_materials(require(root, top, "materials"), top / "materials");
        read_shapes(require(root, top, "shapes"), top / "shapes");
        return std::move(scene_);
    }

  private:
    [[noreturn]] void fail(const Ptr& p, const std::string& problem) const {
        throw SceneError(one_line(scene_.source + ": " + p.str() + ": " + problem));
    }

    // --- generic checks -----------------------------------------------------

    void expect_object(const Json& v, const Ptr& p, const std::string& what) const {
        if (!v.is_object())
            fail(p, "expected " + what + ", got " + describe(v));
    }

    const std::string& expect_string(const Json& v, const Ptr& p) const {
        if (!v.is_string())
            fail(p, "expected a string, got " + describe(v));
        return v.get_ref<const std::string&>();
    }

    const Json& require(const Json& obj, const Ptr& p, const char* key) const {
        const auto it = obj.find(key);
        if (it == obj.end())
            fail(p / key, "missing required field '" + std::string(key) + "'");
        return *it;
    }

    void check_keys(const Json& obj, const Ptr& p,
                    std::initializer_list<std::string_view> allowed) const {
        for (const auto& [key, value] : obj.items()) {
            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end())
                continue;
            std::string list;
            for (const auto a : allowed)
                list += (list.empty() ? "" : ", ") + std::string(a);
            fail(p / key, "unknown key '" + shorten(key, 60) + "' (allowed here: " + list + ")");
        }
    }

    double number(const Json& v, const Ptr& p) const {
        if (!v.is_number())
            fail(p, "expected a number, got " + describe(v));
        const double x = v.get<double>();
        if (!std::isfinite(x))
            fail(p, "expected a finite number, got " + fmt(x));
        return x;
    }

    // A number that must be a whole number (an integral float like 800.0 is fine).
    double whole_number(const Json& v, const Ptr& p) const {
        if (!v.is_number())
            fail(p, "expected an integer, got " + describe(v));
        const double x = number(v, p);
        if (std::floor(x) != x)
            fail(p, "expected an integer, got " + fmt(x));
        return x;
    }

    void check_range(double x, const Ptr& p, Range range) const {
        switch (range) {
        case Range::Coordinate:
            if (std::abs(x) > scene_limits::max_coordinate)
                fail(p, "magnitude too large for float32 rendering (limit 1e30), got " + fmt(x));
            break;
        case Range::Reflectance:
            if (x < 0.0 || x > 1.0)
                fail(p, "reflectance must be in [0, 1], got " + fmt(x));
            break;
        case Range::Radiance:
            if (x < 0.0)
                fail(p, "must not be negative, got " + fmt(x));
            if (x > scene_limits::max_radiance)
                fail(p, "must be at most 1e30 (float32 range), got " + fmt(x));
            break;
        }
    }

    glm::dvec3 vec3(const Json& v, const Ptr& p, Range range) const {
        if (!v.is_array() || v.size() != 3)
            fail(p, "expected an array of 3 numbers, got " + describe(v));
        glm::dvec3 r;
        for (std::size_t i = 0; i < 3; ++i) {
            const double x = number(v[i], p / i);
            check_range(x, p / i, range);
            r[static_cast<glm::length_t>(i)] = x;
        }
        return r;
    }

    // An array of points; exact_count 0 means "at least one".
    std::vector<glm::dvec3> points(const Json& v, const Ptr& p, std::size_t exact_count) const {
        if (!v.is_array())
            fail(p, "expected an array of points ([x, y, z] arrays), got " + describe(v));
        if (exact_count != 0 && v.size() != exact_count)
            fail(p, "expected exactly " + std::to_string(exact_count) +
                        " points ([x, y, z] arrays), got " + describe(v));
        if (v.empty())
            fail(p, "must contain at least one point");
        std::vector<glm::dvec3> r;
        r.reserve(v.size());
        for (std::size_t i = 0; i < v.size(); ++i)
            r.push_back(vec3(v[i], p / i, Range::Coordinate));
        return r;
    }

    // --- camera ---------------------------------------------------------------

    void read_camera(const Json& cam, const Ptr& p) {
        expect_object(cam, p, "an object");
        check_keys(cam, p, {"eye", "look_at", "direction", "up", "fov", "resolution"});
        Camera& c = scene_.camera;
        c.eye = vec3(require(cam, p, "eye"), p / "eye", Range::Coordinate);

        const bool has_look_at = cam.contains("look_at");
        const bool has_direction = cam.contains("direction");
        if (has_look_at && has_direction)
            fail(p / "direction", "give either 'look_at' or 'direction', not both");
        if (!has_look_at && !has_direction)
            fail(p / "look_at", "missing required field 'look_at' (or give 'direction')");
        if (has_look_at) {
            c.look_at = vec3(cam.at("look_at"), p / "look_at", Range::Coordinate);
            if (view_direction_is_degenerate(c.eye, c.look_at))
                fail(p / "look_at", "must differ from eye (there is no view direction)");
        } else {
            const glm::dvec3 d = vec3(cam.at("direction"), p / "direction", Range::Coordinate);
            if (d == glm::dvec3(0.0))
                fail(p / "direction", "must not be the zero vector");
            c.look_at = c.eye + d;
            if (view_direction_is_degenerate(c.eye, c.look_at))
                fail(p / "direction", "too short to be resolved at the eye's distance from the "
                                      "origin (give a longer direction)");
        }
        const char* dir_name = has_look_at ? "look_at - eye" : "direction";

        c.up = vec3(require(cam, p, "up"), p / "up", Range::Coordinate);
        if (c.up == glm::dvec3(0.0))
            fail(p / "up", "must not be the zero vector");
        if (up_is_parallel(c.eye, c.look_at, c.up))
            fail(p / "up", std::string("is parallel to the view direction (") + dir_name +
                               "): the image's orientation is undefined");

        const Ptr pf = p / "fov";
        c.vertical_fov_degrees = number(require(cam, p, "fov"), pf);
        if (!(c.vertical_fov_degrees > 0.0 && c.vertical_fov_degrees < 180.0))
            fail(pf, "vertical field of view must be between 0 and 180 degrees (exclusive), got " +
                         fmt(c.vertical_fov_degrees));

        const Ptr pr = p / "resolution";
        const Json& res = require(cam, p, "resolution");
        if (!res.is_array() || res.size() != 2)
            fail(pr, "expected an array of 2 integers [width, height], got " + describe(res));
        std::array<int, 2> wh{};
        for (std::size_t i = 0; i < 2; ++i) {
            const double x = whole_number(res[i], pr / i);
            if (x < 1.0)
                fail(pr / i, "must be a positive number of pixels, got " + fmt(x));
            if (x > scene_limits::max_resolution)
                fail(pr / i, "must be at most 16384 pixels, got " + fmt(x));
            wh[i] = static_cast<int>(x);
        }
        c.width = wh[0];
        c.height = wh[1];
    }

    // --- materials ------------------------------------------------------------

    void read_materials(const Json& mats, const Ptr& p) {
        expect_object(mats, p, "an object mapping material names to materials");
        if (mats.empty())
            fail(p, "must define at least one material");
        for (const auto& [name, m] : mats.items()) {
            const Ptr pm = p / name;
            expect_object(m, pm, "a material object");
            const std::string& type = expect_string(require(m, pm, "type"), pm / "type");
            Material mat;
            mat.name = name;
            if (type == "diffuse" || type == "mirror") {
                mat.kind = type == "diffuse" ? MaterialKind::Diffuse : MaterialKind::Mirror;
                check_keys(m, pm, {"type", "reflectance", "emission"});
                mat.reflectance =
                    vec3(require(m, pm, "reflectance"), pm / "reflectance", Range::Reflectance);
                if (const auto it = m.find("emission"); it != m.end())
                    mat.emission = vec3(*it, pm / "emission", Range::Radiance);
            } else if (type == "emitter") {
                mat.kind = MaterialKind::Emitter;
                check_keys(m, pm, {"type", "radiance"});
                mat.reflectance = glm::dvec3(0.0);
                mat.emission = vec3(require(m, pm, "radiance"), pm / "radiance", Range::Radiance);
                if (!mat.is_emissive())
                    scene_.warnings.push_back((pm / "radiance").str() +
                                              ": emitter with zero radiance emits nothing");
            } else {
                fail(pm / "type", "unknown material type '" + shorten(type, 40) +
                                      "' (expected diffuse, mirror or emitter)");
            }
            material_index_.emplace(name, static_cast<std::uint32_t>(scene_.materials.size()));
            scene_.materials.push_back(std::move(mat));
        }
    }

    std::uint32_t material_ref(const Json& shape, const Ptr& p) const {
        const Ptr pm = p / "material";
        const std::string& name = expect_string(require(shape, p, "material"), pm);
        const auto it = material_index_.find(name);
        if (it == material_index_.end()) {
            std::string known;
            std::size_t listed = 0;
            for (const Material& m : scene_.materials) {
                if (listed++ == 12) {
                    known += ", ...";
                    break;
                }
                known += (known.empty() ? "" : ", ") + shorten(m.name, 40);
            }
            fail(pm, "unknown material '" + shorten(name, 60) + "' (defined: " + known + ")");
        }
        return it->second;
    }

    // --- shapes ---------------------------------------------------------------

    void add_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      std::uint32_t material, const std::string& where, const char* which) {
        if (is_zero_area(a, b, c)) {
            scene_.warnings.push_back(where + ": skipped zero-area triangle" + which);
            return;
        }
        scene_.triangles.push_back(Triangle{{a, b, c}, material});
    }

    void read_quad(const std::vector<glm::dvec3>& v, std::uint32_t material, const Ptr& p) {
        const bool zero1 = is_zero_area(v[0], v[1], v[2]);
        const bool zero2 = is_zero_area(v[0], v[2], v[3]);
        if (!zero1 || !zero2) {
            const glm::dvec3 n1 = glm::cross(v[1] - v[0], v[2] - v[0]);
            const glm::dvec3 n2 = glm::cross(v[2] - v[0], v[3] - v[0]);
            double size = 0.0;
            for (std::size_t i = 0; i < 4; ++i)
                for (std::size_t j = i + 1; j < 4; ++j)
                    size = std::max(size, glm::length(v[j] - v[i]));
            // The plane of the larger half; the remaining corner must lie on it.
            const bool first = glm::length(n1) >= glm::length(n2);
            const glm::dvec3 n = glm::normalize(first ? n1 : n2);
            const std::size_t other = first ? 3 : 1;
            const double off = std::abs(glm::dot(n, v[other] - v[0]));
            if (off > scene_limits::quad_planarity_relative * size)
                fail(p / "vertices", "the 4 corners are not coplanar: corner " +
                                         std::to_string(other) + " is " + fmt4(off) +
                                         " off the plane of the other three (tolerance 1e-6 x "
                                         "quad size " +
                                         fmt4(size) + ")");
            if (!zero1 && !zero2 && glm::dot(n1, n2) < 0.0)
                fail(p / "vertices",
                     "the quad is folded or not convex at corner 1 or 3: its halves (0, 1, 2) and "
                     "(0, 2, 3) face opposite ways; list the corners in order around the quad");
        }
        const std::string where = p.str();
        add_triangle(v[0], v[1], v[2], material, where, " (corners 0, 1, 2) of the quad");
        add_triangle(v[0], v[2], v[3], material, where, " (corners 0, 2, 3) of the quad");
    }

    void read_mesh(const Json& s, std::uint32_t material, const Ptr& p) {
        const std::vector<glm::dvec3> verts = points(require(s, p, "vertices"), p / "vertices", 0);
        const Ptr pt = p / "triangles";
        const Json& tris = require(s, p, "triangles");
        if (!tris.is_array())
            fail(pt, "expected an array of [i, j, k] vertex index triples, got " + describe(tris));
        if (tris.empty())
            fail(pt, "must contain at least one triangle");
        for (std::size_t t = 0; t < tris.size(); ++t) {
            const Ptr pi = pt / t;
            const Json& tri = tris[t];
            if (!tri.is_array() || tri.size() != 3)
                fail(pi, "expected an array of 3 vertex indices, got " + describe(tri));
            std::array<std::size_t, 3> idx{};
            for (std::size_t k = 0; k < 3; ++k) {
                const double x = whole_number(tri[k], pi / k);
                if (x < 0.0 || x >= static_cast<double>(verts.size()))
                    fail(pi / k, "vertex index " + fmt(x) + " out of range: the mesh has " +
                                     std::to_string(verts.size()) + " vertices (0-based)");
                idx[k] = static_cast<std::size_t>(x);
            }
            add_triangle(verts[idx[0]], verts[idx[1]], verts[idx[2]], material, pi.str(), "");
        }
    }

    void read_sphere(const Json& s, std::uint32_t material, const Ptr& p) {
        Sphere sp;
        sp.center = vec3(require(s, p, "center"), p / "center", Range::Coordinate);
        const Ptr pr = p / "radius";
        sp.radius = number(require(s, p, "radius"), pr);
        if (sp.radius <= 0.0)
            fail(pr, "must be positive, got " + fmt(sp.radius));
        check_range(sp.radius, pr, Range::Coordinate);
        if (scene_.materials[material].is_emissive())
            fail(p / "material", "material '" + shorten(scene_.materials[material].name, 60) +
                                     "' is emissive, but spheres cannot be emitters: use "
                                     "triangles");
        sp.material = material;
        scene_.spheres.push_back(sp);
    }

    void read_shapes(const Json& shapes, const Ptr& p) {
        if (!shapes.is_array())
            fail(p, "expected an array of shapes, got " + describe(shapes));
        if (shapes.empty())
            fail(p, "the scene has no shapes");
        for (std::size_t i = 0; i < shapes.size(); ++i) {
            const Ptr ps = p / i;
            const Json& s = shapes[i];
            expect_object(s, ps, "a shape object");
            const std::string& type = expect_string(require(s, ps, "type"), ps / "type");
            if (type == "triangle" || type == "quad") {
                check_keys(s, ps, {"type", "vertices", "material", "name"});
            } else if (type == "mesh") {
                check_keys(s, ps, {"type", "vertices", "triangles", "material", "name"});
            } else if (type == "sphere") {
                check_keys(s, ps, {"type", "center", "radius", "material", "name"});
            } else {
                fail(ps / "type", "unknown shape type '" + shorten(type, 40) +
                                      "' (expected triangle, quad, mesh or sphere)");
            }
            if (const auto it = s.find("name"); it != s.end())
                expect_string(*it, ps / "name");
            const std::uint32_t material = material_ref(s, ps);

            if (type == "triangle") {
                const auto v = points(require(s, ps, "vertices"), ps / "vertices", 3);
                add_triangle(v[0], v[1], v[2], material, ps.str(), "");
            } else if (type == "quad") {
                read_quad(points(require(s, ps, "vertices"), ps / "vertices", 4), material, ps);
            } else if (type == "mesh") {
                read_mesh(s, material, ps);
            } else {
                read_sphere(s, material, ps);
            }
        }
        if (scene_.triangles.empty() && scene_.spheres.empty())
            fail(p, "every shape was skipped (all triangles have zero area): nothing to render");
    }

    Scene scene_;
    std::unordered_map<std::string, std::uint32_t> material_index_;
};

// 1-based line and column of the byte at 0-based offset `at` (clamped to the text).
std::pair<std::size_t, std::size_t> line_column(std::string_view text, std::size_t at) {
    at = std::min(at, text.size());
    std::size_t line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    return {line, at - line_start + 1};
}

} // namespace

Scene parse_scene(std::string_view json_text, const std::string& source_name) {
    DomBuilder dom;
    const bool ok = Json::sax_parse(json_text.begin(), json_text.end(), &dom);
    if (!ok || dom.failed) {
        std::string msg = source_name;
        if (dom.has_position) {
            const std::size_t at = dom.position == 0 ? 0 : dom.position - 1;
            const auto [line, column] = line_column(json_text, at);
            msg += ":" + std::to_string(line) + ":" + std::to_string(column) + " (byte " +
                   std::to_string(dom.position) + ")";
        }
        msg += ": " + shorten(dom.pointer, 200) + ": " +
               (dom.problem.empty() ? "invalid JSON" : dom.problem);
        throw SceneError(one_line(msg));
    }
    Scene scene = SceneReader(source_name).read(dom.root);
    validate_scene(scene); // a backstop: the reader has already checked all of this
    return scene;
}

Scene load_scene(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::string text;
    try {
        text = read_file_text(path);
    } catch (const FileError& e) {
        throw SceneError(one_line("cannot open scene '" + name + "': " + e.reason()));
    }
    return parse_scene(text, name);
}

} // namespace wp
