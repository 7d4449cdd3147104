// Mitsuba 3's BSDFs as wavepath materials (bsdfs.hpp).
#include "scene/mitsuba/bsdfs.hpp"

#include <algorithm>

#include <glm/common.hpp>

#include "scene/json_reader.hpp"
#include "scene/material.hpp"
#include "scene/mitsuba/parameters.hpp"
#include "scene/mitsuba/textures.hpp"
#include "scene/validate.hpp"

namespace wp::mitsuba {
namespace {

// What reading one BSDF needs besides its parameters: the scene's textures,
// and which of its children (textures) it took.
struct BsdfContext {
    const Object& bsdf;
    TextureTable& textures;
    std::vector<const Object*> taken{};

    // The <texture> nested or referred to under `name`, if any.
    const Object* texture(Parameters& p, const std::string& name) {
        for (std::size_t i = 0; i < bsdf.children.size(); ++i)
            if (const auto& child = bsdf.children[i];
                child->tag == "texture" && bsdf.child_names[i] == name) {
                if (p.find(name))
                    p.fail(name, "given twice: as a value and as a <texture>");
                taken.push_back(child.get());
                return child.get();
            }
        return nullptr;
    }
};

// A colour parameter that may be a texture: the texture's number k + 1 goes
// to `texture`, and the constant becomes its mean (clamped to [0, 1]; the
// BSDF sees the texture's values, the host's heuristics the mean).
glm::dvec3 albedo(Parameters& p, BsdfContext& c, const std::string& name,
                  const glm::dvec3& fallback, std::uint32_t& texture);

// A reflectance or transmittance in [0, 1] per channel, or its default.
glm::dvec3 albedo(Parameters& p, const std::string& name, const glm::dvec3& fallback) {
    const glm::dvec3 value = p.color(name).value_or(fallback);
    check_range(p, name, value, 0.0, 1.0);
    return value;
}

glm::dvec3 albedo(Parameters& p, BsdfContext& c, const std::string& name,
                  const glm::dvec3& fallback, std::uint32_t& texture) {
    if (const Object* t = c.texture(p, name)) {
        texture = c.textures.add(*t);
        return glm::clamp(c.textures.textures()[texture - 1].mean(), 0.0, 1.0);
    }
    return albedo(p, name, fallback);
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
void read_conductor(Parameters& p, BsdfContext& c, Material& m) {
    const std::optional<std::string> metal = p.string("material");
    const std::optional<glm::dvec3> eta = p.color("eta", SpectrumUse::Unbounded),
                                    k = p.color("k", SpectrumUse::Unbounded);
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
    m.reflectance = albedo(p, c, "specular_reflectance", glm::dvec3(1.0), m.reflectance_texture);
}

double roughness(Parameters& p, const std::string& name, double value) {
    if (!(value > 0.0) || value > scene_limits::max_alpha)
        p.fail(name, "must be in (0, 4], got " + json::number_text(value));
    return value;
}

// A roughness given as a texture: its number k + 1, the kernels take its
// luminance (as Mitsuba's float lookups of a colour texture do).
std::uint32_t roughness_texture(Parameters& p, BsdfContext& c, const std::string& name) {
    const Object* t = c.texture(p, name);
    return t ? c.textures.add(*t) : 0u;
}

void read_roughness(Parameters& p, BsdfContext& c, Material& m) {
    const std::string distribution = p.string("distribution").value_or("beckmann");
    if (distribution == "beckmann")
        m.distribution = MicrofacetDistribution::Beckmann;
    else if (distribution == "ggx")
        m.distribution = MicrofacetDistribution::Ggx;
    else
        p.fail("distribution", "unknown distribution '" + json::shorten(distribution, 40) +
                                   "' (expected beckmann or ggx)");
    const std::uint32_t alpha_texture = roughness_texture(p, c, "alpha");
    m.alpha_u_texture = roughness_texture(p, c, "alpha_u");
    m.alpha_v_texture = roughness_texture(p, c, "alpha_v");
    std::optional<double> alpha = p.number("alpha");
    std::optional<double> u = p.number("alpha_u"), v = p.number("alpha_v");
    // A textured roughness counts as given; its constant is unused.
    if (alpha_texture) {
        alpha = 0.1;
        m.alpha_u_texture = m.alpha_v_texture = alpha_texture;
    } else {
        if (m.alpha_u_texture)
            u = 0.1;
        if (m.alpha_v_texture)
            v = 0.1;
    }
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

// The name `child` fills in `parent`.
std::string child_name(const Object& parent, const Object& child) {
    for (std::size_t i = 0; i < parent.children.size(); ++i)
        if (parent.children[i].get() == &child)
            return parent.child_names[i];
    return child.name;
}

// Every child a BSDF's reader did not take (a texture for a parameter that
// takes none, any other plugin) is refused.
void refuse_children(const BsdfContext& c) {
    for (const auto& child : c.bsdf.children) {
        if (std::find(c.taken.begin(), c.taken.end(), child.get()) != c.taken.end())
            continue;
        std::string problem;
        if (child->tag == "texture") {
            const std::string name = child_name(c.bsdf, *child);
            problem = "parameter '" + name + "' of " + c.bsdf.element() +
                      " cannot be a texture in wavepath (textures go to reflectances, "
                      "transmittances and roughness)";
        } else {
            problem = "wavepath does not support a <" + child->tag + "> inside " + c.bsdf.element();
        }
        fail_at(child->where, child->element(), problem);
    }
}

bool reflects_only(MaterialKind kind) {
    return kind != MaterialKind::Dielectric && kind != MaterialKind::ThinDielectric &&
           kind != MaterialKind::RoughDielectric;
}

Material read_plain(const Object& bsdf, TextureTable& textures) {
    Parameters p(bsdf);
    BsdfContext c{bsdf, textures};
    Material m;
    const std::string& type = bsdf.type;
    if (type == "diffuse") {
        m.kind = MaterialKind::Diffuse;
        m.reflectance = albedo(p, c, "reflectance", glm::dvec3(0.5), m.reflectance_texture);
    } else if (type == "conductor") {
        m.kind = MaterialKind::Conductor;
        const bool numbers = p.find("eta") || p.find("k");
        read_conductor(p, c, m);
        // As the JSON loader does: the default, "none" without eta and k, is
        // the perfect mirror, with the mirror kind's next-event estimation
        // (which takes one colour: a textured one stays a conductor).
        if (m.metal == "none" && !numbers && !m.is_textured())
            m.kind = MaterialKind::Mirror;
    } else if (type == "roughconductor") {
        m.kind = MaterialKind::RoughConductor;
        read_conductor(p, c, m);
        read_roughness(p, c, m);
    } else if (type == "dielectric" || type == "thindielectric" || type == "roughdielectric") {
        m.kind = type == "dielectric"       ? MaterialKind::Dielectric
                 : type == "thindielectric" ? MaterialKind::ThinDielectric
                                            : MaterialKind::RoughDielectric;
        m.int_ior = ior(p, "int_ior", 1.5046);
        m.ext_ior = ior(p, "ext_ior", 1.000277);
        m.reflectance =
            albedo(p, c, "specular_reflectance", glm::dvec3(1.0), m.reflectance_texture);
        m.transmittance =
            albedo(p, c, "specular_transmittance", glm::dvec3(1.0), m.transmittance_texture);
        if (m.kind == MaterialKind::RoughDielectric)
            read_roughness(p, c, m);
    } else if (type == "plastic" || type == "roughplastic") {
        m.kind = type == "plastic" ? MaterialKind::Plastic : MaterialKind::RoughPlastic;
        m.int_ior = ior(p, "int_ior", 1.49);
        m.ext_ior = ior(p, "ext_ior", 1.000277);
        m.reflectance = albedo(p, c, "diffuse_reflectance", glm::dvec3(0.5), m.reflectance_texture);
        m.specular = albedo(p, c, "specular_reflectance", glm::dvec3(1.0), m.specular_texture);
        m.nonlinear = p.boolean("nonlinear").value_or(false);
        if (m.kind == MaterialKind::RoughPlastic) {
            if (p.find("alpha_u") || p.find("alpha_v"))
                p.fail(p.find("alpha_u") ? "alpha_u" : "alpha_v",
                       "roughplastic's roughness is isotropic (Mitsuba refuses alpha_u and "
                       "alpha_v too): give alpha");
            read_roughness(p, c, m);
            // Its coating's transmittance table depends on alpha: one per material.
            if (m.alpha_u_texture)
                p.fail("alpha", "roughplastic's roughness cannot be a texture in wavepath (its "
                                "coating's transmittance table is computed once per material)");
        }
    } else {
        p.fail("unsupported BSDF type '" + json::shorten(type, 40) +
               "' (wavepath reads diffuse, conductor, roughconductor, dielectric, "
               "thindielectric, roughdielectric, plastic, roughplastic and twosided)");
    }
    refuse_children(c);
    p.finish();
    return m;
}

} // namespace

Material read_bsdf(const Object& bsdf, TextureTable& textures, std::vector<std::string>& warnings) {
    if (bsdf.tag != "bsdf")
        fail_at(bsdf.where, bsdf.element(), "expected a <bsdf> here, not a <" + bsdf.tag + ">");
    if (bsdf.type != "twosided") {
        Material m = read_plain(bsdf, textures);
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
    Material m = read_plain(inner, textures);
    if (!reflects_only(m.kind))
        fail_at(inner.where, inner.element(),
                "twosided cannot hold a BSDF that transmits light (as in Mitsuba): a dielectric "
                "has two sides of its own");
    return m;
}

} // namespace wp::mitsuba
