// A plugin's parameters as its reader takes them: each by name and kind,
// once; whatever the reader did not take is refused when it finishes, with
// the list of what it reads there. Mitsuba warns about a parameter no plugin
// reads; wavepath refuses it, since a parameter it does not read is one it
// would render without (docs/mitsuba-import.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/mitsuba/spectrum.hpp"
#include "scene/mitsuba/xml_reader.hpp"

namespace wp::mitsuba {

class Parameters {
  public:
    explicit Parameters(const Object& object) : object_(object) {}

    // Each returns nothing when the parameter is absent, and refuses one of
    // another kind. number() takes <float> and <integer>; color() takes
    // <rgb>, <float> (a grey) and <spectrum>: a single value is a grey,
    // wavelength:value pairs become RGB as Mitsuba's RGB mode makes them
    // for that use (spectrum.hpp).
    std::optional<double> number(const std::string& name);
    std::optional<long long> integer(const std::string& name);
    std::optional<bool> boolean(const std::string& name);
    std::optional<std::string> string(const std::string& name);
    std::optional<glm::dvec3> point(const std::string& name); // <point> or <vector>
    std::optional<glm::dvec3> color(const std::string& name,
                                    SpectrumUse use = SpectrumUse::Reflectance);
    std::optional<wp::Transform> transform(const std::string& name);
    // A parameter that changes nothing wavepath renders (a clipping plane
    // that keeps the scene, a sampler's seed): read and dropped.
    void ignore(const std::string& name);

    // The parameter of this name, if there is one (to point a message at it).
    const Parameter* find(const std::string& name) const;

    // Refuses the first parameter nobody took.
    void finish() const;

    [[noreturn]] void fail(const std::string& problem) const;
    [[noreturn]] void fail(const std::string& name, const std::string& problem) const;

    const Object& object() const { return object_; }

  private:
    const Parameter* take(const std::string& name, std::initializer_list<ValueKind> kinds);

    const Object& object_;
    std::vector<std::string> known_; // every name asked for, in order
    std::vector<std::string> taken_;
};

// `value` must be in [lo, hi]; `what` as in "must be in [0, 1]".
void check_range(Parameters& p, const std::string& name, const glm::dvec3& value, double lo,
                 double hi);

} // namespace wp::mitsuba
