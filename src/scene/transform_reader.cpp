#include "scene/transform_reader.hpp"

#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace wp {

namespace {

using json::describe;
using json::Json;
using json::shorten;
using Ptr = json::Pointer;

// Any finite numbers: the transformed mesh is checked against the scene's
// coordinate limit by load_mesh, so the step's own values need no range.
glm::dvec3 vector3(const json::Reader& r, const Json& v, const Ptr& p) {
    if (!v.is_array() || v.size() != 3)
        r.fail(p, "expected an array of 3 numbers, got " + describe(v));
    return {r.number(v[0], p / 0), r.number(v[1], p / 1), r.number(v[2], p / 2)};
}

Transform rotate(const json::Reader& r, const Json& v, const Ptr& p) {
    r.expect_object(v, p, "an object {\"angle\": degrees, \"axis\": [x, y, z]}");
    r.check_keys(v, p, {"angle", "axis"});
    const double degrees = r.number(r.require(v, p, "angle"), p / "angle");
    return Transform::rotate(degrees, vector3(r, r.require(v, p, "axis"), p / "axis"));
}

Transform scale(const json::Reader& r, const Json& v, const Ptr& p) {
    if (v.is_number())
        return Transform::scale(r.number(v, p));
    if (!v.is_array())
        r.fail(p, "expected a number or an array of 3 numbers, got " + describe(v));
    return Transform::scale(vector3(r, v, p));
}

Transform look_at(const json::Reader& r, const Json& v, const Ptr& p) {
    r.expect_object(v, p, "an object with from, to and up");
    r.check_keys(v, p, {"from", "to", "up"});
    return Transform::look_at(vector3(r, r.require(v, p, "from"), p / "from"),
                              vector3(r, r.require(v, p, "to"), p / "to"),
                              vector3(r, r.require(v, p, "up"), p / "up"));
}

Transform matrix(const json::Reader& r, const Json& v, const Ptr& p) {
    if (!v.is_array() || v.size() != 4)
        r.fail(p, "expected 4 rows of 4 numbers, got " + describe(v));
    std::array<double, 16> rows{};
    for (std::size_t row = 0; row < 4; ++row) {
        const Json& values = v[row];
        if (!values.is_array() || values.size() != 4)
            r.fail(p / row, "expected a row of 4 numbers, got " + describe(values));
        for (std::size_t column = 0; column < 4; ++column)
            rows[row * 4 + column] = r.number(values[column], p / row / column);
    }
    return Transform::from_rows(rows);
}

Transform step(const json::Reader& r, const Json& v, const Ptr& p) {
    const char* const kinds = "translate, rotate, scale, look_at or matrix";
    r.expect_object(v, p, std::string("a transform step: an object with one key (") + kinds + ")");
    if (v.size() != 1)
        r.fail(p, "a transform step has exactly one key (" + std::string(kinds) + "), got " +
                      std::to_string(v.size()));
    const auto only = v.begin();
    const std::string& kind = only.key();
    const Json& value = only.value();
    const Ptr pv = p / kind;
    // The factories name themselves in their messages ("rotate: ..."), so the
    // step's pointer is enough to locate the problem.
    try {
        if (kind == "translate")
            return Transform::translate(vector3(r, value, pv));
        if (kind == "rotate")
            return rotate(r, value, pv);
        if (kind == "scale")
            return scale(r, value, pv);
        if (kind == "look_at")
            return look_at(r, value, pv);
        if (kind == "matrix")
            return matrix(r, value, pv);
    } catch (const TransformError& e) {
        r.fail(p, e.what());
    }
    r.fail(pv, "unknown transform step '" + shorten(kind, 40) + "' (expected " + kinds + ")");
}

} // namespace

Transform read_transform(const json::Reader& reader, const Json& steps, const Ptr& p) {
    if (!steps.is_array())
        reader.fail(p, "expected an array of transform steps, got " + describe(steps));
    std::vector<Transform> list;
    list.reserve(steps.size());
    for (std::size_t i = 0; i < steps.size(); ++i)
        list.push_back(step(reader, steps[i], p / i));
    // A product that overflows is caught where it matters: load_mesh checks
    // every transformed vertex against the scene's coordinate limit.
    return Transform::compose(list);
}

} // namespace wp
