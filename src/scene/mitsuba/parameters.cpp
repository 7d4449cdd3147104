// A plugin's parameters, each taken once (parameters.hpp).
#include "scene/mitsuba/parameters.hpp"

#include <algorithm>

#include "scene/json_reader.hpp"

namespace wp::mitsuba {

const Parameter* Parameters::find(const std::string& name) const {
    for (const Parameter& p : object_.parameters)
        if (p.name == name)
            return &p;
    return nullptr;
}

const Parameter* Parameters::take(const std::string& name, std::initializer_list<ValueKind> kinds) {
    if (std::find(known_.begin(), known_.end(), name) == known_.end())
        known_.push_back(name);
    const Parameter* p = find(name);
    if (!p)
        return nullptr;
    taken_.push_back(name);
    if (std::find(kinds.begin(), kinds.end(), p->kind) == kinds.end()) {
        std::string expected;
        for (ValueKind k : kinds)
            expected += (expected.empty() ? "<" : " or <") + std::string(value_tag(k)) + ">";
        fail_at(p->where, p->element,
                "'" + name + "' of " + object_.element() + " must be " + expected + ", not <" +
                    value_tag(p->kind) + ">");
    }
    return p;
}

std::optional<double> Parameters::number(const std::string& name) {
    const Parameter* p = take(name, {ValueKind::Float, ValueKind::Integer});
    if (!p)
        return std::nullopt;
    return p->kind == ValueKind::Integer ? static_cast<double>(p->integer) : p->number;
}

std::optional<long long> Parameters::integer(const std::string& name) {
    const Parameter* p = take(name, {ValueKind::Integer});
    return p ? std::optional<long long>(p->integer) : std::nullopt;
}

std::optional<bool> Parameters::boolean(const std::string& name) {
    const Parameter* p = take(name, {ValueKind::Boolean});
    return p ? std::optional<bool>(p->boolean) : std::nullopt;
}

std::optional<std::string> Parameters::string(const std::string& name) {
    const Parameter* p = take(name, {ValueKind::String});
    return p ? std::optional<std::string>(p->text) : std::nullopt;
}

std::optional<glm::dvec3> Parameters::point(const std::string& name) {
    const Parameter* p = take(name, {ValueKind::Point, ValueKind::Vector});
    return p ? std::optional<glm::dvec3>(p->vector) : std::nullopt;
}

std::optional<glm::dvec3> Parameters::color(const std::string& name, SpectrumUse use) {
    // A texture under this name (<texture name="reflectance">) is refused
    // by the reader that finds it among the object's children.
    const Parameter* p = take(name, {ValueKind::Rgb, ValueKind::Spectrum, ValueKind::Float});
    if (!p)
        return std::nullopt;
    if (!p->wavelengths.empty())
        return spectrum_to_rgb(p->wavelengths, p->values, use);
    return p->kind == ValueKind::Float ? glm::dvec3(p->number) : p->vector;
}

std::optional<wp::Transform> Parameters::transform(const std::string& name) {
    const Parameter* p = take(name, {ValueKind::Transform});
    return p ? std::optional<wp::Transform>(p->transform) : std::nullopt;
}

void Parameters::ignore(const std::string& name) {
    if (std::find(known_.begin(), known_.end(), name) == known_.end())
        known_.push_back(name);
    if (find(name))
        taken_.push_back(name);
}

void Parameters::finish() const {
    for (const Parameter& p : object_.parameters) {
        if (std::find(taken_.begin(), taken_.end(), p.name) != taken_.end())
            continue;
        std::string known;
        for (const std::string& k : known_)
            known += (known.empty() ? "" : ", ") + k;
        fail_at(p.where, p.element,
                "wavepath does not support the parameter '" + json::shorten(p.name, 40) + "' of " +
                    object_.element() + " (it reads " + (known.empty() ? "none" : known) + ")");
    }
}

void Parameters::fail(const std::string& problem) const {
    fail_at(object_.where, object_.element(), problem);
}

void Parameters::fail(const std::string& name, const std::string& problem) const {
    if (const Parameter* p = find(name))
        fail_at(p->where, p->element, problem);
    fail(name + ": " + problem);
}

void check_range(Parameters& p, const std::string& name, const glm::dvec3& value, double lo,
                 double hi) {
    for (int i = 0; i < 3; ++i)
        if (!(value[i] >= lo && value[i] <= hi))
            p.fail(name, "must be in [" + json::number_text(lo) + ", " + json::number_text(hi) +
                             "], got " + json::number_text(value[i]));
}

} // namespace wp::mitsuba
