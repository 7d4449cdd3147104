// JSON with diagnostics: the layer under the scene loader (scene/load.cpp)
// that turns text into a DOM and reads typed values out of it, so that every
// problem becomes one SceneError naming the source, the value (as a JSON
// pointer, RFC 6901) and, for syntax errors, the line, column and byte:
//   "hexroom.json:3:14 (byte 52): /camera/fov: invalid JSON: ..."
//   "hexroom.json: /shapes/3/radius: expected a number, got \"two\""
// It knows nothing of scenes beyond the error type.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "util/one_line.hpp"

namespace wp::json {

// ordered_json keeps the file's order, so that (for example) materials get
// indices in the order the file lists them.
using Json = nlohmann::ordered_json;
using Pointer = Json::json_pointer;

// Arrays and objects nest at most this deep; a scene needs 4.
inline constexpr std::size_t kMaxNesting = 64;

// Parses `text` through a SAX handler, so that every error (syntax, a
// number that overflows to infinity, a duplicate key, which would silently
// replace the earlier value, nesting deeper than kMaxNesting) comes with the
// pointer of the value being read.
// Throws SceneError("<source>[:<line>:<column> (byte <n>)]: <pointer>: <problem>").
Json parse(std::string_view text, const std::string& source);

// The pointer as messages print it: "(root)" for the whole document.
std::string pointer_text(const Pointer& p);

// The shortest text that reads back as x ("0.1", "1e+30").
std::string number_text(double x);

// A short description of a value for "expected X, got Y" messages: the
// value itself for scalars (strings shortened), "an array of 3 elements",
// "an object".
std::string describe(const Json& v);

// Messages are one line of valid UTF-8: control characters and bytes that
// are not well-formed UTF-8 (from keys or names) become '?' (util/one_line.hpp).
using wp::one_line;

// s shortened to at most n bytes plus "...", without cutting a UTF-8 sequence.
std::string shorten(const std::string& s, std::size_t n);

// Typed reads from a document parsed from `source`; each throws
// SceneError("<source>: <pointer>: <problem>") when the value is not what
// it must be.
class Reader {
  public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void fail(const Pointer& p, const std::string& problem) const;

    void expect_object(const Json& v, const Pointer& p, const std::string& what) const;
    const std::string& expect_string(const Json& v, const Pointer& p) const;
    // obj[key], which must be present; p is obj's pointer.
    const Json& require(const Json& obj, const Pointer& p, const char* key) const;
    // Fails on the first key of obj that is not in `allowed`, listing them.
    void check_keys(const Json& obj, const Pointer& p,
                    std::initializer_list<std::string_view> allowed) const;
    // A finite number.
    double number(const Json& v, const Pointer& p) const;
    // A number that must be a whole number (an integral float like 800.0 is fine).
    double whole_number(const Json& v, const Pointer& p) const;

  private:
    std::string source_;
};

} // namespace wp::json
