// Mitsuba 3's BSDFs as wavepath materials (bsdfs.hpp).
#include "scene/mitsuba/bsdfs.hpp"

#include "scene/json_reader.hpp"
#include "scene/material.hpp"
#include "scene/mitsuba/parameters.hpp"
#include "scene/validate.hpp"

namespace wp::mitsuba {
namespace {

// A reflectance or transmittance in [0, 1] per channel, or its default.
glm::dvec3 albedo(Parameters& p, const std::string& name, const glm::dvec3& fallback) {
    const glm::dvec3 value = p.color(name).value_or(fallback);
    check_range(p, name, value, 0.0, 1.0);
    return value;
}

// int_ior or ext_ior: a number, or a name of Mitsuba's table.
double ior(Parameters& p, const std::string& name, double fallback) {
    if (const Parameter* given = p.find(name); given && given->kind == ValueKind::String) {
        const std::string text = *p.string(name);
        if (const NamedIor* named = find_ior(text))
            return named->ior;
        std::string known;
        for (const NamedIor& n : named_iors())
            known += (known.empty() ? "" : ", ") + std::string(n.name);
        p.fail(name, "unknown index of refraction '" + json::shorten(text, 40) +
                         "' (expected a number or " + known + ")");
    }
    const double value = p.number(name).value_or(fallback);
    if (!(value > 0.0) || value > scene_limits::max_index)
        p.fail(name, "must be in (0, 1e4], got " + json::number_text(value));
    return value;
}

// Mitsuba's conductor parameters: a named metal or eta and k (default the
// perfect mirror, "none"), and specular_reflectance on top.
void read_conductor(Parameters& p, Material& m) {
    const std::optional<std::string> metal = p.string("material");
    const std::optional<glm::dvec3> eta = p.color("eta"), k = p.color("k");
    m.metal = metal.value_or("none");
    if (metal && (eta || k))
        p.fail("material", "give either a named material or eta and k, not both");
    if (m.metal != "none") {
        const NamedMetal* named = find_metal(m.metal);
        if (!named) {
            std::string known = "none";
            for (const NamedMetal& n : named_metals())
                known += std::string(", ") + n.name;
            p.fail("material", "unknown metal '" + json::shorten(m.metal, 40) + "' (wavepath has " +
                                   known + ")");
        }
        m.eta = named->eta;
        m.k = named->k;
    }
    if (eta) {
        check_range(p, "eta", *eta, 0.0, scene_limits::max_index);
        m.eta = *eta;
        m.metal.clear();
    }
    if (k) {
        check_range(p, "k", *k, 0.0, scene_limits::max_index);
        m.k = *k;
        m.metal.clear();
    }
    m.reflectance = albedo(p, "specular_reflectance", glm::dvec3(1.0));
}

double roughness(Parameters& p, const std::string& name, double value) {
    if (!(value > 0.0) || value > scene_limits::max_alpha)
        p.fail(name, "must be in (0, 4], got " + json::number_text(value));
    return value;
}

void read_roughness(Parameters& p, Material& m) {
    const std::string distribution = p.string("distribution").value_or("beckmann");
    if (distribution == "beckmann")
        m.distribution = MicrofacetDistribution::Beckmann;
    else if (distribution == "ggx")
        m.distribution = MicrofacetDistribution::Ggx;
    else
        p.fail("distribution", "unknown distribution '" + json::shorten(distribution, 40) +
                                   "' (expected beckmann or ggx)");
    const std::optional<double> alpha = p.number("alpha");
    const std::optional<double> u = p.number("alpha_u"), v = p.number("alpha_v");
    if (alpha && (u || v))
        p.fail("alpha", "give either alpha or alpha_u and alpha_v, not both");
    if (u.has_value() != v.has_value())
        p.fail(u ? "alpha_u" : "alpha_v", "alpha_u and alpha_v go together");
    if (u) {
        m.alpha_u = roughness(p, "alpha_u", *u);
        m.alpha_v = roughness(p, "alpha_v", *v);
    } else {
        m.alpha_u = m.alpha_v = roughness(p, "alpha", alpha.value_or(0.1));
    }
    // Sampling the visible normals or all of them changes the noise only.
    p.ignore("sample_visible");
}

// Textures are the one kind of child a BSDF could have here, and wavepath
// has none yet.
void refuse_children(const Object& bsdf) {
    for (const auto& child : bsdf.children)
        fail_at(child->where, child->element(),
                child->tag == "texture"
                    ? "textures are not supported yet: give '" + child->name + "' of " +
                          bsdf.element() + " as <rgb>, <spectrum> or <float>"
                    : "wavepath does not support a <" + child->tag + "> inside " + bsdf.element());
}

bool reflects_only(MaterialKind kind) {
    return kind != MaterialKind::Dielectric && kind != MaterialKind::ThinDielectric &&
           kind != MaterialKind::RoughDielectric;
}

Material read_plain(const Object& bsdf) {
    Parameters p(bsdf);
    Material m;
    const std::string& type = bsdf.type;
    if (type == "diffuse") {
        m.kind = MaterialKind::Diffuse;
        m.reflectance = albedo(p, "reflectance", glm::dvec3(0.5));
    } else if (type == "conductor") {
        m.kind = MaterialKind::Conductor;
        const bool numbers = p.find("eta") || p.find("k");
        read_conductor(p, m);
        // As the JSON loader does: the default, "none" without eta and k, is
        // the perfect mirror, with the mirror kind's next-event estimation.
        if (m.metal == "none" && !numbers)
            m.kind = MaterialKind::Mirror;
    } else if (type == "roughconductor") {
        m.kind = MaterialKind::RoughConductor;
        read_conductor(p, m);
        read_roughness(p, m);
    } else if (type == "dielectric" || type == "thindielectric" || type == "roughdielectric") {
        m.kind = type == "dielectric"       ? MaterialKind::Dielectric
                 : type == "thindielectric" ? MaterialKind::ThinDielectric
                                            : MaterialKind::RoughDielectric;
        m.int_ior = ior(p, "int_ior", 1.5046);
        m.ext_ior = ior(p, "ext_ior", 1.000277);
        m.reflectance = albedo(p, "specular_reflectance", glm::dvec3(1.0));
        m.transmittance = albedo(p, "specular_transmittance", glm::dvec3(1.0));
        if (m.kind == MaterialKind::RoughDielectric)
            read_roughness(p, m);
    } else if (type == "plastic" || type == "roughplastic") {
        m.kind = type == "plastic" ? MaterialKind::Plastic : MaterialKind::RoughPlastic;
        m.int_ior = ior(p, "int_ior", 1.49);
        m.ext_ior = ior(p, "ext_ior", 1.000277);
        m.reflectance = albedo(p, "diffuse_reflectance", glm::dvec3(0.5));
        m.specular = albedo(p, "specular_reflectance", glm::dvec3(1.0));
        m.nonlinear = p.boolean("nonlinear").value_or(false);
        if (m.kind == MaterialKind::RoughPlastic) {
            if (p.find("alpha_u") || p.find("alpha_v"))
                p.fail(p.find("alpha_u") ? "alpha_u" : "alpha_v",
                       "roughplastic's roughness is isotropic (Mitsuba refuses alpha_u and "
                       "alpha_v too): give alpha");
            read_roughness(p, m);
        }
    } else {
        p.fail("unsupported BSDF type '" + json::shorten(type, 40) +
               "' (wavepath reads diffuse, conductor, roughconductor, dielectric, "
               "thindielectric, roughdielectric, plastic, roughplastic and twosided)");
    }
    refuse_children(bsdf);
    p.finish();
    return m;
}

} // namespace

Material read_bsdf(const Object& bsdf, std::vector<std::string>& warnings) {
    if (bsdf.tag != "bsdf")
        fail_at(bsdf.where, bsdf.element(), "expected a <bsdf> here, not a <" + bsdf.tag + ">");
    if (bsdf.type != "twosided") {
        Material m = read_plain(bsdf);
        const bool black = m.reflectance == glm::dvec3(0.0) && m.kind == MaterialKind::Diffuse;
        if (reflects_only(m.kind) && !black)
            warnings.push_back(bsdf.where.text() + ": " + bsdf.element() +
                               ": one-sided in Mitsuba (black from behind), but wavepath's " +
                               material_kind_name(m.kind) +
                               " reflects on both sides; wrap it in <bsdf type=\"twosided\"> "
                               "for the same image");
        return m;
    }
    Parameters p(bsdf);
    p.finish();
    // Two different BSDFs for the two sides: wavepath has one per surface.
    if (bsdf.children.size() != 1 &&
        !(bsdf.children.size() == 2 && bsdf.children[0] == bsdf.children[1]))
        p.fail("a twosided BSDF needs exactly one nested BSDF (wavepath has no different BSDFs "
               "for the two sides), got " +
               std::to_string(bsdf.children.size()));
    const Object& inner = *bsdf.children.front();
    if (inner.tag != "bsdf")
        fail_at(inner.where, inner.element(), "expected a <bsdf> inside " + bsdf.element());
    if (inner.type == "twosided")
        fail_at(inner.where, inner.element(), "a twosided BSDF inside a twosided BSDF");
    Material m = read_plain(inner);
    if (!reflects_only(m.kind))
        fail_at(inner.where, inner.element(),
                "twosided cannot hold a BSDF that transmits light (as in Mitsuba): a dielectric "
                "has two sides of its own");
    return m;
}

} // namespace wp::mitsuba
