#include "scene/material.hpp"

#include <cstddef>
#include <tuple>
#include <type_traits>

namespace wp {

const char* material_kind_name(MaterialKind kind) {
    switch (static_cast<wp_uint>(kind)) {
#define WP_MATERIAL_NAME_CASE(KIND, Name, name, value, bsdf, glossy)                               \
    case value:                                                                                    \
        return #name;
        WP_MATERIALS(WP_MATERIAL_NAME_CASE)
#undef WP_MATERIAL_NAME_CASE
    default:
        return nullptr;
    }
}

const char* emitter_kind_name(EmitterKind kind) {
    switch (kind) {
    case EmitterKind::Point:
        return "point";
    case EmitterKind::Spot:
        return "spot";
    case EmitterKind::Directional:
        return "directional";
    case EmitterKind::Constant:
        return "constant";
    }
    return nullptr;
}

std::optional<MaterialKind> material_kind_from_name(std::string_view name) {
#define WP_MATERIAL_FROM_NAME(KIND, Name, name_, value, bsdf, glossy)                              \
    if (name == #name_)                                                                            \
        return MaterialKind::Name;
    WP_MATERIALS(WP_MATERIAL_FROM_NAME)
#undef WP_MATERIAL_FROM_NAME
    return std::nullopt;
}

std::string material_kind_names() {
    std::string out;
#define WP_MATERIAL_LIST_NAME(KIND, Name, name, value, bsdf, glossy)                               \
    out += out.empty() ? #name : ", " #name;
    WP_MATERIALS(WP_MATERIAL_LIST_NAME)
#undef WP_MATERIAL_LIST_NAME
    return out;
}

// The table's values are its rows' order (checkpoints hash them).
#define WP_MATERIAL_VALUE_CHECK(KIND, Name, name, value, bsdf, glossy)                             \
    static_assert(static_cast<wp_uint>(MaterialKind::Name) == WP_MATERIAL_##KIND);
WP_MATERIALS(WP_MATERIAL_VALUE_CHECK)
#undef WP_MATERIAL_VALUE_CHECK

const std::vector<NamedMetal>& named_metals() {
    // RGB (linear sRGB primaries) eta and k of the measured spectral data that
    // Mitsuba ships for its named conductors (Palik's "Handbook of Optical
    // Constants of Solids" and others, Mitsuba's data/ior), as reduced to RGB
    // by Tungsten (B. Bitterli, src/core/bsdfs/ComplexIorData.hpp). Mitsuba 3
    // renders them spectrally or reduces them itself, so an RGB render agrees
    // with its own only to a few percent in colour.
    static const std::vector<NamedMetal> metals = {
        {"Ag",
         {0.1552646489, 0.1167232965, 0.1383806959},
         {4.8283433224, 3.1222459278, 2.1469504455}},
        {"Al",
         {1.6574599595, 0.8803689579, 0.5212287346},
         {9.2238691996, 6.2695232477, 4.8370012281}},
        {"Au",
         {0.1431189557, 0.3749570432, 1.4424785571},
         {3.9831604247, 2.3857207478, 1.6032152899}},
        {"Cr",
         {4.3696828663, 2.9167024892, 1.6547005413},
         {5.2064337956, 4.2313645277, 3.7549467933}},
        {"Cu",
         {0.2004376970, 0.9240334304, 1.1022119527},
         {3.9129485033, 2.4528477015, 2.1421879552}},
    };
    return metals;
}

const NamedMetal* find_metal(std::string_view name) {
    for (const NamedMetal& m : named_metals())
        if (name == m.name)
            return &m;
    return nullptr;
}

const std::vector<NamedIor>& named_iors() {
    // Mitsuba 3's table (include/mitsuba/render/ior.h), with its source:
    // mostly Hecht, "Optics", 4th edition, measured between 0 and 20 degrees
    // Celsius at about 589 nm.
    static const std::vector<NamedIor> iors = {
        {"vacuum", 1.0},      {"helium", 1.000036},        {"hydrogen", 1.000132},
        {"air", 1.000277},    {"carbon dioxide", 1.00045}, {"water", 1.3330},
        {"acetone", 1.36},    {"ethanol", 1.361},          {"carbon tetrachloride", 1.461},
        {"glycerol", 1.4729}, {"benzene", 1.501},          {"silicone oil", 1.52045},
        {"bromine", 1.661},   {"water ice", 1.31},         {"fused quartz", 1.458},
        {"pyrex", 1.470},     {"acrylic glass", 1.49},     {"polypropylene", 1.49},
        {"bk7", 1.5046},      {"sodium chloride", 1.544},  {"amber", 1.55},
        {"pet", 1.5750},      {"diamond", 2.419},
    };
    return iors;
}

double fresnel_diffuse_reflectance(double eta) {
    const double inv = 1.0 / eta;
    if (eta < 1.0)
        return 0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681;
    return 0.919317 +
           inv * (-3.4793 + inv * (6.75335 + inv * (-7.80989 + inv * (4.98554 + inv * -1.36881))));
}

const NamedIor* find_ior(std::string_view name) {
    for (const NamedIor& i : named_iors())
        if (name == i.name)
            return &i;
    return nullptr;
}

// Material::rendered_fields() must name every member but `name` and `metal`
// (which only label values that are hashed): count the aggregate's members by
// the longest brace initialiser that compiles.
namespace {

struct AnyMember {
    template <typename T> operator T() const;
};

template <typename T, typename... Members> constexpr std::size_t member_count() {
    if constexpr (requires { T{Members{}..., AnyMember{}}; })
        return member_count<T, Members..., AnyMember>();
    else
        return sizeof...(Members);
}

static_assert(member_count<Material>() ==
                  std::tuple_size_v<decltype(std::declval<Material>().rendered_fields())> + 2,
              "a new Material member must be in rendered_fields() (the checkpoint's scene hash)");

} // namespace

} // namespace wp
