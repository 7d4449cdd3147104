// PLY (Turk 1994, the format the Stanford scans ship in), written here rather
// than taken from assimp: the format is small, assimp (libassimp-dev) pulls in a
// large library for one reader, and its messages do not name the element that is
// wrong. Reads ASCII, binary_little_endian and binary_big_endian bodies:
//   - vertex: x y z of any scalar type, in any order, with optional nx ny nz and
//     texture coordinates (u v, s t, texture_u texture_v or texture_s texture_t,
//     the names Mitsuba reads); other properties (colour, confidence, ...) are
//     skipped;
//   - face: a list named vertex_indices (or vertex_index) of any integer count and
//     index types; other face properties are skipped;
//   - tristrips: a vertex_indices list of strips separated by -1, each strip
//     giving triangles of alternating winding (as OpenGL does);
//   - any other element (edge, material, range_grid, ...): skipped.
// Every error names the element and its 0-based index, e.g.
//   "bunny.ply: face 12: vertex index 40000 out of range (35947 vertices)";
// header errors name the header line.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "scene/mesh.hpp"
#include "scene/parse_number.hpp"
#include "scene/polygon_mesh.hpp"
#include "util/one_line.hpp"

namespace wp {

namespace {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct ScalarTypeName {
    std::string_view name;
    ScalarType type;
};
// Both the original names and the sized ones that newer writers use.
constexpr ScalarTypeName scalar_type_names[] = {
    {"char", ScalarType::Int8},      {"int8", ScalarType::Int8},
    {"uchar", ScalarType::UInt8},    {"uint8", ScalarType::UInt8},
    {"short", ScalarType::Int16},    {"int16", ScalarType::Int16},
    {"ushort", ScalarType::UInt16},  {"uint16", ScalarType::UInt16},
    {"int", ScalarType::Int32},      {"int32", ScalarType::Int32},
    {"uint", ScalarType::UInt32},    {"uint32", ScalarType::UInt32},
    {"float", ScalarType::Float32},  {"float32", ScalarType::Float32},
    {"double", ScalarType::Float64}, {"float64", ScalarType::Float64},
};

std::size_t size_of(ScalarType t) {
    switch (t) {
    case ScalarType::Int8:
    case ScalarType::UInt8:
        return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16:
        return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32:
        return 4;
    case ScalarType::Float64:
        return 8;
    }
    return 0;
}

bool is_integer(ScalarType t) {
    return t != ScalarType::Float32 && t != ScalarType::Float64;
}

// The name the header gave the type first in scalar_type_names ("uchar").
std::string_view type_name(ScalarType t) {
    for (const ScalarTypeName& n : scalar_type_names)
        if (n.type == t)
            return n.name;
    return "?";
}

// The values an integer type holds. A binary body cannot hold others, but an
// ASCII one can ("300" as a uchar list count).
struct IntegerRange {
    std::int64_t lowest;
    std::int64_t highest;
};
IntegerRange integer_range(ScalarType t) {
    switch (t) {
    case ScalarType::Int8:
        return {INT8_MIN, INT8_MAX};
    case ScalarType::UInt8:
        return {0, UINT8_MAX};
    case ScalarType::Int16:
        return {INT16_MIN, INT16_MAX};
    case ScalarType::UInt16:
        return {0, UINT16_MAX};
    case ScalarType::Int32:
        return {INT32_MIN, INT32_MAX};
    case ScalarType::UInt32:
    case ScalarType::Float32:
    case ScalarType::Float64:
        break;
    }
    return {0, UINT32_MAX};
}

// What a property means to us; everything else is read and skipped.
enum class Role { Skip, X, Y, Z, NX, NY, NZ, U, V, FaceIndices, StripIndices };

struct Property {
    std::string name;
    bool is_list = false;
    ScalarType type = ScalarType::Float32;     // of the value, or of each list entry
    ScalarType count_type = ScalarType::UInt8; // of a list's length
    Role role = Role::Skip;
};

enum class ElementKind { Vertex, Face, Strips, Other };

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    std::size_t line = 0; // of its header line, for messages
    ElementKind kind = ElementKind::Other;
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::size_t body_offset = 0; // first byte after the end_header line
    std::size_t body_first_line = 0;
};

class HeaderParser {
  public:
    HeaderParser(const std::filesystem::path& file, const std::string& bytes)
        : file_(file), bytes_(bytes) {}

    Header parse() {
        Header header;
        bool have_format = false;
        std::size_t pos = 0;
        std::size_t n = 0;
        for (;;) {
            const std::size_t end = bytes_.find('\n', pos);
            if (end == std::string::npos)
                throw MeshError::in_file(file_, "PLY header has no end_header line");
            std::string_view line(bytes_.data() + pos, end - pos);
            pos = end + 1;
            ++n;
            if (!line.empty() && line.back() == '\r')
                line.remove_suffix(1);
            std::string_view rest = line;
            const std::string_view keyword = next_token(rest);
            if (n == 1) {
                if (keyword != "ply" || !next_token(rest).empty())
                    fail(n, "not a PLY file (the first line is not 'ply')");
                continue;
            }
            if (keyword == "end_header") {
                if (!have_format)
                    fail(n, "PLY header has no format line");
                header.body_offset = pos;
                header.body_first_line = n + 1;
                break;
            }
            if (keyword == "comment" || keyword == "obj_info" || keyword.empty())
                continue;
            if (keyword == "format") {
                const std::string_view f = next_token(rest);
                if (f == "ascii")
                    header.format = Format::Ascii;
                else if (f == "binary_little_endian")
                    header.format = Format::BinaryLittleEndian;
                else if (f == "binary_big_endian")
                    header.format = Format::BinaryBigEndian;
                else
                    fail(n, "unknown PLY format '" + excerpt(f) + "'");
                have_format = true;
            } else if (keyword == "element") {
                header.elements.push_back(element(rest, n, header.elements));
            } else if (keyword == "property") {
                if (header.elements.empty())
                    fail(n, "property before any element");
                header.elements.back().properties.push_back(property(rest, n));
            } else {
                fail(n, "unknown PLY header line '" + excerpt(line) + "'");
            }
        }
        for (Element& e : header.elements)
            assign_roles(e);
        return header;
    }

  private:
    [[noreturn]] void fail(std::size_t line, const std::string& message) const {
        throw MeshError::at_line(file_, line, message);
    }

    Element element(std::string_view rest, std::size_t n, const std::vector<Element>& previous) {
        Element e;
        e.name = std::string(next_token(rest));
        const std::string_view count = next_token(rest);
        std::int64_t c = 0;
        if (e.name.empty() || !parse_integer(count, c) || c < 0 || !next_token(rest).empty())
            fail(n, "expected 'element <name> <count>'");
        e.count = static_cast<std::uint64_t>(c);
        e.line = n;
        for (const Element& p : previous)
            if (p.name == e.name)
                fail(n, "element '" + excerpt(e.name) + "' appears twice");
        return e;
    }

    ScalarType scalar_type(std::string_view word, std::size_t n) const {
        for (const ScalarTypeName& t : scalar_type_names)
            if (t.name == word)
                return t.type;
        fail(n, "unknown PLY property type '" + excerpt(word) + "'");
    }

    Property property(std::string_view rest, std::size_t n) {
        Property p;
        std::string_view word = next_token(rest);
        if (word == "list") {
            p.is_list = true;
            p.count_type = scalar_type(next_token(rest), n);
            if (!is_integer(p.count_type))
                fail(n, "list length type must be an integer type");
            word = next_token(rest);
        }
        p.type = scalar_type(word, n);
        p.name = std::string(next_token(rest));
        if (p.name.empty() || !next_token(rest).empty())
            fail(n, "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
        return p;
    }

    void assign_roles(Element& e) const {
        for (std::size_t i = 0; i < e.properties.size(); ++i)
            for (std::size_t j = 0; j < i; ++j)
                if (e.properties[i].name == e.properties[j].name)
                    fail(e.line, "element '" + excerpt(e.name) + "' has property '" +
                                     excerpt(e.properties[i].name) + "' twice");
        if (e.name == "vertex") {
            e.kind = ElementKind::Vertex;
            const std::pair<const char*, Role> slots[] = {{"x", Role::X},   {"y", Role::Y},
                                                          {"z", Role::Z},   {"nx", Role::NX},
                                                          {"ny", Role::NY}, {"nz", Role::NZ}};
            int normals = 0;
            for (const auto& [name, role] : slots) {
                Property* p = find(e, name);
                if (!p) {
                    if (role == Role::X || role == Role::Y || role == Role::Z)
                        fail(e.line, std::string("vertex element has no '") + name + "' property");
                    continue;
                }
                if (p->is_list)
                    fail(e.line, std::string("vertex property '") + name + "' is a list");
                p->role = role;
                if (role == Role::NX || role == Role::NY || role == Role::NZ)
                    ++normals;
            }
            if (normals != 0 && normals != 3)
                fail(e.line, "vertex element has only some of nx, ny, nz");
            // Texture coordinates under the names Mitsuba reads, as a pair.
            const std::pair<const char*, const char*> uv_names[] = {
                {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
            for (const auto& [u_name, v_name] : uv_names) {
                Property* u = find(e, u_name);
                Property* v = find(e, v_name);
                if (!u && !v)
                    continue;
                if (!u || !v)
                    fail(e.line, std::string("vertex element has '") + (u ? u_name : v_name) +
                                     "' without '" + (u ? v_name : u_name) + "'");
                if (u->is_list || v->is_list)
                    fail(e.line, std::string("vertex property '") + u_name + "' or '" + v_name +
                                     "' is a list");
                u->role = Role::U;
                v->role = Role::V;
                break;
            }
        } else if (e.name == "face" || e.name == "tristrips") {
            const bool face = e.name == "face";
            e.kind = face ? ElementKind::Face : ElementKind::Strips;
            Property* p = find(e, "vertex_indices");
            if (!p && face)
                p = find(e, "vertex_index");
            if (!p)
                fail(e.line, excerpt(e.name) + " element has no vertex_indices list");
            if (!p->is_list || !is_integer(p->type))
                fail(e.line, excerpt(e.name) + " property '" + excerpt(p->name) +
                                 "' must be a list of integers");
            p->role = face ? Role::FaceIndices : Role::StripIndices;
        }
    }

    static Property* find(Element& e, std::string_view name) {
        for (Property& p : e.properties)
            if (p.name == name)
                return &p;
        return nullptr;
    }

    const std::filesystem::path& file_;
    const std::string& bytes_;
};

// A problem inside one element; the body reader adds the element and index.
struct BodyProblem {
    std::string message;
};

// Values of a binary body, in the file's byte order.
class BinarySource {
  public:
    BinarySource(const std::string& bytes, std::size_t offset, bool big_endian)
        : p_(bytes.data() + offset), end_(bytes.data() + bytes.size()),
          swap_(big_endian != (std::endian::native == std::endian::big)) {}

    std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
    // A lower bound on the bytes one value of type t takes here.
    static std::size_t min_size(ScalarType t) { return size_of(t); }

    // False at the end of the data.
    // One value stored as type t, into a double or an int64 (for which the
    // header checks have excluded float types). False at the end of the data.
    template <typename Out> bool value(ScalarType t, Out& out) {
        switch (t) {
        case ScalarType::Int8:
            return get<std::int8_t>(out);
        case ScalarType::UInt8:
            return get<std::uint8_t>(out);
        case ScalarType::Int16:
            return get<std::int16_t>(out);
        case ScalarType::UInt16:
            return get<std::uint16_t>(out);
        case ScalarType::Int32:
            return get<std::int32_t>(out);
        case ScalarType::UInt32:
            return get<std::uint32_t>(out);
        case ScalarType::Float32:
        case ScalarType::Float64:
            if constexpr (std::is_integral_v<Out>)
                throw BodyProblem{"integer expected"};
            else
                return t == ScalarType::Float32 ? get<float>(out) : get<double>(out);
        }
        return false;
    }
    bool real(ScalarType t, double& out) { return value(t, out); }
    bool integer(ScalarType t, std::int64_t& out) { return value(t, out); }

    bool skip(ScalarType t, std::uint64_t n) {
        const std::uint64_t bytes = n * size_of(t);
        if (bytes > remaining())
            return false;
        p_ += bytes;
        return true;
    }

  private:
    template <class T, class Out> bool get(Out& out) {
        if (remaining() < sizeof(T))
            return false;
        unsigned char raw[sizeof(T)];
        std::memcpy(raw, p_, sizeof(T));
        if (swap_)
            std::reverse(raw, raw + sizeof(T));
        T value;
        std::memcpy(&value, raw, sizeof(T));
        out = static_cast<Out>(value);
        p_ += sizeof(T);
        return true;
    }

    const char* p_;
    const char* end_;
    bool swap_;
};

// Values of an ASCII body: whitespace-separated words, lines counted for messages.
class AsciiSource {
  public:
    AsciiSource(const std::string& bytes, std::size_t offset, std::size_t first_line)
        : p_(bytes.data() + offset), end_(bytes.data() + bytes.size()), line_(first_line) {}

    std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
    // One digit and one separator.
    static std::size_t min_size(ScalarType) { return 2; }
    std::size_t line() const { return line_; }

    bool real(ScalarType t, double& out) {
        std::string_view w;
        if (!word(w))
            return false;
        if (is_integer(t)) {
            std::int64_t i = 0;
            if (!parse_integer(w, i))
                bad(w, "an integer");
            out = static_cast<double>(i);
        } else if (!parse_double(w, out)) {
            bad(w, "a number");
        }
        return true;
    }

    bool integer(ScalarType t, std::int64_t& out) {
        std::string_view w;
        if (!word(w))
            return false;
        if (!parse_integer(w, out))
            bad(w, "an integer");
        check_fits(t, out);
        return true;
    }

    bool skip(ScalarType, std::uint64_t n) {
        std::string_view w;
        for (std::uint64_t i = 0; i < n; ++i)
            if (!word(w))
                return false;
        return true;
    }

  private:
    bool word(std::string_view& w) {
        while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n')) {
            if (*p_ == '\n')
                ++line_;
            ++p_;
        }
        const char* begin = p_;
        while (p_ < end_ && !(*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n'))
            ++p_;
        w = std::string_view(begin, static_cast<std::size_t>(p_ - begin));
        return !w.empty();
    }

    // List counts and entries only: else a count of 300 declared uchar is read
    // as 300, and the entries it claims reported as a truncated file. (A scalar
    // past its type, a colour of 300, is read as written: its meaning is plain.)
    void check_fits(ScalarType t, std::int64_t value) const {
        if (!is_integer(t))
            return; // an integer where floats are declared: the float is exact enough
        const IntegerRange range = integer_range(t);
        if (value < range.lowest || value > range.highest)
            throw BodyProblem{"line " + std::to_string(line_) + ": " + std::to_string(value) +
                              " does not fit the declared type " + std::string(type_name(t)) +
                              " (" + std::to_string(range.lowest) + " to " +
                              std::to_string(range.highest) + ")"};
    }

    [[noreturn]] void bad(std::string_view w, const char* expected) const {
        throw BodyProblem{"line " + std::to_string(line_) + ": expected " + expected + ", got '" +
                          excerpt(w) + "'"};
    }

    const char* p_;
    const char* end_;
    std::size_t line_;
};

template <class Source> class BodyReader {
  public:
    BodyReader(const std::filesystem::path& file, const Header& header, Source& source)
        : file_(file), header_(header), in_(source) {
        for (const Element& e : header.elements)
            if (e.kind == ElementKind::Vertex)
                vertex_count_ = e.count;
    }

    PolygonMesh read() {
        const Element* current = nullptr;
        std::uint64_t index = 0;
        try {
            for (const Element& e : header_.elements) {
                current = &e;
                reserve(e);
                for (index = 0; index < e.count; ++index)
                    read_one(e);
            }
        } catch (const BodyProblem& p) {
            throw MeshError::at_element(file_, current->name, static_cast<std::size_t>(index),
                                        p.message);
        }
        return std::move(mesh_);
    }

  private:
    // Reserves no more than the remaining data can hold, so that a header that
    // claims 10^12 vertices gives "file ends early", not an allocation failure.
    void reserve(const Element& e) {
        std::size_t min_bytes = 0;
        for (const Property& p : e.properties)
            min_bytes += Source::min_size(p.is_list ? p.count_type : p.type);
        const std::uint64_t fits = in_.remaining() / std::max<std::size_t>(min_bytes, 1);
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(e.count, fits));
        if (e.kind == ElementKind::Vertex) {
            mesh_.positions.reserve(n);
            if (has_normals(e))
                mesh_.normals.reserve(n);
            if (has_uvs(e))
                mesh_.uvs.reserve(n);
        } else if (e.kind == ElementKind::Face) {
            mesh_.offsets.reserve(n + 1);
            mesh_.polygon_materials.reserve(n);
            mesh_.indices.reserve(3 * n);
        }
    }

    static bool has_uvs(const Element& e) {
        return std::any_of(e.properties.begin(), e.properties.end(),
                           [](const Property& p) { return p.role == Role::U; });
    }

    static bool has_normals(const Element& e) {
        return std::any_of(e.properties.begin(), e.properties.end(),
                           [](const Property& p) { return p.role == Role::NX; });
    }

    [[noreturn]] static void truncated() { throw BodyProblem{"file ends early (truncated?)"}; }

    void read_one(const Element& e) {
        double slot[8] = {0, 0, 0, 0, 0, 0, 0, 0}; // x y z nx ny nz u v
        for (const Property& p : e.properties) {
            if (!p.is_list) {
                double v = 0.0;
                if (!in_.real(p.type, v))
                    truncated();
                if (p.role >= Role::X && p.role <= Role::V)
                    slot[static_cast<int>(p.role) - static_cast<int>(Role::X)] = v;
                continue;
            }
            std::int64_t n = 0;
            if (!in_.integer(p.count_type, n))
                truncated();
            if (n < 0)
                throw BodyProblem{"list '" + excerpt(p.name) + "' has negative length " +
                                  std::to_string(n)};
            if (p.role == Role::Skip) {
                if (!in_.skip(p.type, static_cast<std::uint64_t>(n)))
                    truncated();
                continue;
            }
            // Checked before reading so a corrupt length cannot make a huge buffer.
            if (static_cast<std::uint64_t>(n) > in_.remaining() / Source::min_size(p.type) + 1)
                truncated();
            list_.clear();
            for (std::int64_t k = 0; k < n; ++k) {
                std::int64_t i = 0;
                if (!in_.integer(p.type, i))
                    truncated();
                list_.push_back(i);
            }
            if (p.role == Role::FaceIndices)
                add_face();
            else
                add_strips();
        }
        if (e.kind == ElementKind::Vertex)
            add_vertex(e, slot);
    }

    void add_vertex(const Element& e, const double* slot) {
        const glm::dvec3 p(slot[0], slot[1], slot[2]);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw BodyProblem{"coordinate is not finite"};
        mesh_.positions.push_back(p);
        if (has_normals(e)) {
            const glm::dvec3 n(slot[3], slot[4], slot[5]);
            if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
                throw BodyProblem{"normal is not finite"};
            if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0)
                throw BodyProblem{"normal has zero length"};
            mesh_.normals.push_back(n);
        }
        if (has_uvs(e)) {
            const glm::dvec2 uv(slot[6], slot[7]);
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
                throw BodyProblem{"texture coordinate is not finite"};
            mesh_.uvs.push_back(uv);
        }
    }

    std::uint32_t checked_index(std::int64_t i) const {
        if (i < 0 || static_cast<std::uint64_t>(i) >= vertex_count_)
            throw BodyProblem{"vertex index " + std::to_string(i) + " out of range (" +
                              std::to_string(vertex_count_) + " vertices)"};
        return static_cast<std::uint32_t>(i);
    }

    void add_face() {
        if (list_.size() < 3)
            throw BodyProblem{"face has " + std::to_string(list_.size()) +
                              " vertices, needs at least 3"};
        corners_.clear();
        for (const std::int64_t i : list_)
            corners_.push_back(checked_index(i));
        mesh_.add_polygon(corners_, 0);
    }

    // Each run between -1 markers is a strip: corners (a, b, c, d, ...) give the
    // triangles (a, b, c), (c, b, d), (c, d, e), ... so all share the winding of
    // the first. Runs shorter than three corners give no triangles.
    void add_strips() {
        std::size_t run_start = 0;
        for (std::size_t k = 0; k <= list_.size(); ++k) {
            if (k < list_.size() && list_[k] != -1) {
                (void)checked_index(list_[k]);
                continue;
            }
            for (std::size_t j = run_start; j + 2 < k; ++j) {
                const std::uint32_t a = static_cast<std::uint32_t>(list_[j]);
                const std::uint32_t b = static_cast<std::uint32_t>(list_[j + 1]);
                const std::uint32_t c = static_cast<std::uint32_t>(list_[j + 2]);
                const std::uint32_t odd[3] = {b, a, c};
                const std::uint32_t even[3] = {a, b, c};
                mesh_.add_polygon((j - run_start) % 2 ? odd : even, 0);
            }
            run_start = k + 1;
        }
    }

    const std::filesystem::path& file_;
    const Header& header_;
    Source& in_;
    std::uint64_t vertex_count_ = 0;
    PolygonMesh mesh_;
    std::vector<std::int64_t> list_;
    std::vector<std::uint32_t> corners_;
};

} // namespace

PolygonMesh read_ply(const std::filesystem::path& file, const std::string& bytes) {
    const Header header = HeaderParser(file, bytes).parse();
    const auto vertex =
        std::find_if(header.elements.begin(), header.elements.end(),
                     [](const Element& e) { return e.kind == ElementKind::Vertex; });
    if (vertex == header.elements.end())
        throw MeshError::in_file(file, "PLY header declares no vertex element");
    if (vertex->count > UINT32_MAX)
        throw MeshError::at_line(file, vertex->line, "more than 2^32 - 1 vertices");

    if (header.format == Format::Ascii) {
        AsciiSource source(bytes, header.body_offset, header.body_first_line);
        return BodyReader<AsciiSource>(file, header, source).read();
    }
    BinarySource source(bytes, header.body_offset, header.format == Format::BinaryBigEndian);
    return BodyReader<BinarySource>(file, header, source).read();
}

} // namespace wp
