#include "scene/json_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <unordered_set>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace wp::json {
namespace {

// ---------------------------------------------------------------------------
// JSON text -> DOM, through a SAX handler so that every error (syntax, number
// overflow, duplicate key) comes with the JSON pointer of the value being read
// and, where the parser knows it, the byte position.

class DomBuilder final : public nlohmann::json_sax<Json> {
  public:
    Json root;

    bool failed = false;
    bool too_deep = false; // the SAX interface gives no position for it: see deep_position
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
        if (!enter())
            return false;
        Json* v = place(Json::object());
        frames_.push_back(Frame{v, false, 0, {}, {}});
        return true;
    }
    bool key(string_t& val) override {
        Frame& f = frames_.back();
        auto& members = f.value->get_ref<Json::object_t&>();
        if (is_duplicate(f, members, val)) {
            failed = true;
            pointer = pointer_text(path(frames_.size() - 1) / val);
            problem = "duplicate key '" + shorten(val, 60) +
                      "' (the later value would silently replace the earlier one)";
            return false;
        }
        f.key = val;
        f.in_member = true;
        // The key is new (checked above), so append it directly: ordered_json's
        // operator[] searches the members linearly first, which made an object
        // of n members (a scene's materials) take n^2 / 2 comparisons.
        members.Container::emplace_back(val, nullptr);
        pending_ = &members.back().second;
        return true;
    }
    bool end_object() override {
        frames_.pop_back();
        return true;
    }
    bool start_array(std::size_t /*elements*/) override {
        if (!enter())
            return false;
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
        pointer = pointer_text(error_path());
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
            if (!frames_.empty() && !frames_.back().is_array && !frames_.back().in_member)
                problem += frames_.back().key.empty()
                               ? " (in the object's first key)"
                               : " (in the key after '" + shorten(frames_.back().key, 60) + "')";
        }
        return false;
    }

  private:
    // Refuses to go deeper than kMaxNesting: later passes over the DOM (and
    // its destructor) recurse once per level, so a value nested a million
    // deep would overflow the stack instead of failing with a message.
    bool enter() {
        if (frames_.size() < kMaxNesting)
            return true;
        failed = true;
        too_deep = true;
        pointer = pointer_text(error_path());
        problem = "values nested more than " + std::to_string(kMaxNesting) + " levels deep";
        return false;
    }

    // Objects up to this size are checked for duplicate keys by a scan of
    // their members; larger ones (a scene's materials) get a hash set, so the
    // check stays linear without a set for every small object.
    static constexpr std::size_t kScanLimit = 16;

    struct Frame;
    static bool is_duplicate(Frame& f, const Json::object_t& members, const std::string& key) {
        if (members.size() < kScanLimit)
            return std::any_of(members.begin(), members.end(),
                               [&](const auto& member) { return member.first == key; });
        if (f.keys.empty())
            for (const auto& member : members)
                f.keys.insert(member.first);
        return !f.keys.insert(key).second;
    }

    struct Frame {
        Json* value;
        bool is_array;
        std::size_t count; // elements placed so far (arrays)
        std::string key;   // the member being read (objects)
        std::unordered_set<std::string> keys;
        // Objects: between a key and the end of its value. Outside, the
        // parser is reading the next key, and an error there (say invalid
        // UTF-8) is in that key, not in `key`'s value.
        bool in_member = false;
    };

    // Pointer to the value being read inside the first n frames.
    Pointer path(std::size_t n) const {
        Pointer p;
        for (std::size_t i = 0; i < n; ++i) {
            const Frame& f = frames_[i];
            p = f.is_array ? p / (f.count == 0 ? std::size_t{0} : f.count - 1) : p / f.key;
        }
        return p;
    }

    // Where a parse error happened: inside an array, the element after the
    // last one that was placed.
    Pointer error_path() const {
        if (frames_.empty())
            return Pointer();
        const Frame& top = frames_.back();
        Pointer p = path(frames_.size() - 1);
        if (top.is_array)
            return p / top.count;
        return top.in_member ? p / top.key : p;
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
        f.in_member = false; // a container's end comes later, but its errors are inside it
        return pending_;
    }
    bool put(Json&& v) {
        place(std::move(v));
        return true;
    }

    std::vector<Frame> frames_;
    Json* pending_ = nullptr; // the object member whose value comes next
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

// Offset of the bracket that opens level `depth` + 1, skipping strings; the
// text's size if none does. Only called after the parser stopped there, so
// the text up to it is valid JSON.
std::size_t deep_position(std::string_view text, std::size_t depth) {
    std::size_t level = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++level > depth)
                return i;
        } else if (c == ']' || c == '}') {
            --level;
        }
    }
    return text.size();
}

} // namespace

std::string number_text(double x) {
    std::array<char, 64> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
    return std::string(buf.data(), res.ptr);
}

std::string shorten(const std::string& s, std::size_t n) {
    return excerpt(s, n);
}

std::string pointer_text(const Pointer& p) {
    return p.empty() ? std::string("(root)") : p.to_string();
}

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
        return number_text(v.get<double>());
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

Json parse(std::string_view text, const std::string& source) {
    DomBuilder dom;
    const bool ok = Json::sax_parse(text.begin(), text.end(), &dom);
    if (!ok || dom.failed) {
        if (dom.too_deep) {
            dom.has_position = true;
            dom.position = deep_position(text, kMaxNesting) + 1;
        }
        std::string msg = source;
        if (dom.has_position) {
            const std::size_t at = dom.position == 0 ? 0 : dom.position - 1;
            const auto [line, column] = line_column(text, at);
            msg += ":" + std::to_string(line) + ":" + std::to_string(column) + " (byte " +
                   std::to_string(dom.position) + ")";
        }
        msg += ": " + shorten(dom.pointer, 200) + ": " +
               (dom.problem.empty() ? "invalid JSON" : dom.problem);
        throw SceneError(one_line(msg));
    }
    return std::move(dom.root);
}

void Reader::fail(const Pointer& p, const std::string& problem) const {
    throw SceneError(one_line(source_ + ": " + pointer_text(p) + ": " + problem));
}

void Reader::expect_object(const Json& v, const Pointer& p, const std::string& what) const {
    if (!v.is_object())
        fail(p, "expected " + what + ", got " + describe(v));
}

const std::string& Reader::expect_string(const Json& v, const Pointer& p) const {
    if (!v.is_string())
        fail(p, "expected a string, got " + describe(v));
    return v.get_ref<const std::string&>();
}

const Json& Reader::require(const Json& obj, const Pointer& p, const char* key) const {
    const auto it = obj.find(key);
    if (it == obj.end())
        fail(p / key, "missing required field '" + std::string(key) + "'");
    return *it;
}

void Reader::check_keys(const Json& obj, const Pointer& p,
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

double Reader::number(const Json& v, const Pointer& p) const {
    if (!v.is_number())
        fail(p, "expected a number, got " + describe(v));
    const double x = v.get<double>();
    if (!std::isfinite(x))
        fail(p, "expected a finite number, got " + number_text(x));
    return x;
}

double Reader::whole_number(const Json& v, const Pointer& p) const {
    if (!v.is_number())
        fail(p, "expected an integer, got " + describe(v));
    const double x = number(v, p);
    if (std::floor(x) != x)
        fail(p, "expected an integer, got " + number_text(x));
    return x;
}

} // namespace wp::json
