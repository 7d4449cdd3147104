#include "scene/material.hpp"

#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <tuple>
#include <type_traits>
#include <utility>

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
    case EmitterKind::Envmap:
        return "envmap";
    }
    return nullptr;
}

bool has_sphere_lights(const Scene& scene) {
    for (const Sphere& s : scene.spheres)
        if (s.material < scene.materials.size() && scene.materials[s.material].is_emissive())
            return true;
    return false;
}

bool has_lights_besides_triangles(const Scene& scene) {
    return !scene.emitters.empty() || has_sphere_lights(scene);
}

const Emitter* find_environment(const std::vector<Emitter>& emitters) {
    for (const Emitter& e : emitters)
        if (e.kind == EmitterKind::Constant || e.kind == EmitterKind::Envmap)
            return &e;
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

namespace {

// ---- the rough coating's integrals (roughplastic) -------------------------------
//
// Mitsuba integrates the coating's transmittance and reflectance for a
// direction wi by quadrature over the unit square of its visible-normal
// sampling: Gauss-Legendre nodes in both numbers (32 x 32 for eta > 1, 128 x
// 128 otherwise), each node's normal m weighed by the Fresnel term and the
// masking of the outgoing direction. The same quadrature over the same
// mapping is done here in double precision (Mitsuba's is in float), so that
// the tables agree with Mitsuba's to float rounding, not just to the
// integrals' value (measured against mitsuba 3.9.1: docs/materials.md).

using V3 = glm::dvec3;

// The n Gauss-Legendre nodes in [-1, 1] and their weights (Newton's method on
// the Legendre polynomial from the Chebyshev guesses).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(static_cast<std::size_t>(n), 0.0);
    weights.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-16)
                break;
        }
        nodes[static_cast<std::size_t>(i)] = x;
        weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
}

// The inverse error function: Giles' single-precision fit, polished by
// Newton's method on std::erf to double precision.
double erfinv(double y) {
    y = std::clamp(y, -1.0 + 1e-15, 1.0 - 1e-15);
    double w = -std::log((1.0 - y) * (1.0 + y)), p;
    if (w < 5.0) {
        w -= 2.5;
        p = 2.81022636e-08;
        for (double c : {3.43273939e-07, -3.5233877e-06, -4.39150654e-06, 0.00021858087,
                         -0.00125372503, -0.00417768164, 0.246640727, 1.50140941})
            p = c + p * w;
    } else {
        w = std::sqrt(w) - 3.0;
        p = -0.000200214257;
        for (double c : {0.000100950558, 0.00134934322, -0.00367342844, 0.00573950773,
                         -0.0076224613, 0.00943887047, 1.00167406, 2.83297682})
            p = c + p * w;
    }
    double x = p * y;
    for (int i = 0; i < 2; ++i)
        x -= (std::erf(x) - y) / (2.0 / std::sqrt(std::numbers::pi) * std::exp(-x * x));
    return x;
}

// Shirley and Chiu's concentric map of the unit square onto the disk, as
// Mitsuba's square_to_uniform_disk_concentric orients it.
std::pair<double, double> concentric_disk(double u1, double u2) {
    const double x = 2.0 * u1 - 1.0, y = 2.0 * u2 - 1.0;
    if (x == 0.0 && y == 0.0)
        return {0.0, 0.0};
    const bool steep = std::abs(x) < std::abs(y);
    const double r = steep ? y : x, rp = steep ? x : y;
    double phi = 0.25 * std::numbers::pi * rp / r;
    if (steep)
        phi = 0.5 * std::numbers::pi - phi;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// The quadrature's nodes in the unit square, with what of the
// visible-normal mapping depends on one node alone (computed once per
// resolution: the integrals reuse them for every direction).
struct Quadrature {
    int res = 0;
    std::vector<double> u, weight;               // nodes in [0, 1] and their weights
    std::vector<std::pair<double, double>> disk; // GGX: the concentric map of (u[j], u[k])
    std::vector<double> beckmann_y;              // Beckmann: the slope along y of u[k]
};

Quadrature make_quadrature(int res) {
    Quadrature q;
    q.res = res;
    std::vector<double> nodes;
    gauss_legendre(res, nodes, q.weight);
    for (double x : nodes)
        q.u.push_back(0.5 * x + 0.5);
    for (double a : q.u) {
        for (double b : q.u)
            q.disk.push_back(concentric_disk(a, b));
        q.beckmann_y.push_back(erfinv(2.0 * std::clamp(a, 1e-6, 1.0 - 1e-6) - 1.0));
    }
    return q;
}

const Quadrature& quadrature(int res) {
    static const Quadrature coarse = make_quadrature(32), fine = make_quadrature(128);
    return res == 32 ? coarse : fine;
}

struct Distribution {
    bool ggx;
    double alpha;

    double g1(const V3& v, const V3& m) const {
        if (!(glm::dot(v, m) * v.z > 0.0))
            return 0.0;
        const double xy = alpha * alpha * (v.x * v.x + v.y * v.y);
        if (xy == 0.0)
            return 1.0;
        const double t2 = xy / (v.z * v.z);
        if (ggx)
            return 2.0 / (1.0 + std::sqrt(1.0 + t2));
        const double a = 1.0 / std::sqrt(t2);
        if (a >= 1.6)
            return 1.0;
        return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
    }
};

// Mitsuba's sample_visible_11 for GGX: the slope (alpha 1, in the x-z plane)
// of a normal visible from a direction of cosine cos_theta, from a point of
// the unit disk.
std::pair<double, double> ggx_visible_slope(double cos_theta, double sin_theta,
                                            std::pair<double, double> disk) {
    auto [x, y] = disk;
    const double s = 0.5 * (1.0 + cos_theta);
    y = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - x * x)) + s * y;
    const double z = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
    const double norm = 1.0 / (sin_theta * y + cos_theta * z);
    return {(cos_theta * y - sin_theta * z) * norm, x * norm};
}

// ... and for Beckmann the slope along x, from the first number (Newton's
// method on the slope's CDF, from Mitsuba's initial guess, three steps).
double beckmann_visible_slope_x(double cos_theta, double sin_theta, double u1) {
    const double inv_sqrt_pi = 1.0 / std::sqrt(std::numbers::pi);
    const double tan_theta = sin_theta / cos_theta, cot_theta = 1.0 / tan_theta;
    const double maxval = std::erf(cot_theta);
    u1 = std::clamp(u1, 1e-6, 1.0 - 1e-6);
    double x = maxval - (maxval + 1.0) * std::erf(std::sqrt(-std::log(u1)));
    u1 *= 1.0 + maxval + inv_sqrt_pi * tan_theta * std::exp(-cot_theta * cot_theta);
    for (int i = 0; i < 3; ++i) {
        const double slope = erfinv(x);
        const double value = 1.0 + x + inv_sqrt_pi * tan_theta * std::exp(-slope * slope) - u1;
        x -= value / (1.0 - slope * tan_theta);
    }
    return erfinv(x);
}

// A dielectric's reflectance at incidence cosine cos_i (> 0) for relative
// index eta, and the cosine of the refracted direction (0 under total
// internal reflection).
double fresnel(double cos_i, double eta, double& cos_t) {
    const double cos_t2 = 1.0 - (1.0 - cos_i * cos_i) / (eta * eta);
    if (cos_t2 <= 0.0) {
        cos_t = 0.0;
        return 1.0;
    }
    cos_t = std::sqrt(cos_t2);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// Mitsuba's eval_transmittance (transmit) or eval_reflectance for direction
// wi (wi.z > 0) and relative index eta.
double coating_integral(const Distribution& d, const V3& wi, double eta, bool transmit) {
    const Quadrature& q = quadrature(eta > 1.0 ? 32 : 128);
    // The visible normals of wi: stretch to alpha 1, sample there, rotate to
    // wi's azimuth and unstretch (Mitsuba's MicrofacetDistribution::sample).
    const V3 stretched = glm::normalize(V3(d.alpha * wi.x, d.alpha * wi.y, wi.z));
    const double sin2 = stretched.x * stretched.x + stretched.y * stretched.y;
    const double cos_theta = stretched.z,
                 sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    double cos_phi = 1.0, sin_phi = 0.0;
    if (sin2 > 0.0) {
        cos_phi = std::clamp(stretched.x / std::sqrt(sin2), -1.0, 1.0);
        sin_phi = std::clamp(stretched.y / std::sqrt(sin2), -1.0, 1.0);
    }
    const std::size_t res = static_cast<std::size_t>(q.res);
    double sum = 0.0;
    for (std::size_t j = 0; j < res; ++j) {
        const double beckmann_x =
            d.ggx ? 0.0 : beckmann_visible_slope_x(cos_theta, sin_theta, q.u[j]);
        for (std::size_t k = 0; k < res; ++k) {
            const auto [sx, sy] = d.ggx
                                      ? ggx_visible_slope(cos_theta, sin_theta, q.disk[j * res + k])
                                      : std::pair{beckmann_x, q.beckmann_y[k]};
            const V3 m = glm::normalize(V3(-(cos_phi * sx - sin_phi * sy) * d.alpha,
                                           -(sin_phi * sx + cos_phi * sy) * d.alpha, 1.0));
            const double cos_i = glm::dot(wi, m);
            double cos_t;
            const double f = fresnel(cos_i, eta, cos_t);
            double value;
            if (transmit) {
                // refracted about m, below the surface
                const V3 wo = m * (cos_i / eta - cos_t) - wi / eta;
                value = wo.z < 0.0 && f < 1.0 ? d.g1(wo, m) * (1.0 - f) : 0.0;
            } else {
                const V3 wo = 2.0 * cos_i * m - wi;
                value = wo.z > 0.0 ? d.g1(wo, m) * f : 0.0;
            }
            sum += value * q.weight[j] * q.weight[k] * 0.25;
        }
    }
    return sum;
}

} // namespace

RoughCoating rough_coating(MicrofacetDistribution distribution, double alpha, double eta) {
    const Distribution d{distribution == MicrofacetDistribution::Ggx, std::max(alpha, 1e-4)};
    RoughCoating out;
    double reflectance = 0.0;
    for (int i = 0; i < WP_ROUGH_TRANSMITTANCE_RES; ++i) {
        const double mu = std::max(1e-6, double(i) / (WP_ROUGH_TRANSMITTANCE_RES - 1));
        const V3 wi(std::sqrt(1.0 - mu * mu), 0.0, mu);
        out.transmittance.push_back(coating_integral(d, wi, eta, true));
        reflectance += coating_integral(d, wi, 1.0 / eta, false) * mu;
    }
    // Mitsuba's estimate of 2 * integral of R(mu) mu dmu: twice the mean over
    // the table's cosines.
    out.internal_reflectance = 2.0 * reflectance / WP_ROUGH_TRANSMITTANCE_RES;
    return out;
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
