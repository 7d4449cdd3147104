// The Mitsuba 3 export (mitsuba_export.hpp; what maps to what is in
// docs/mitsuba-export.md).
#include "scene/mitsuba_export.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>

#include "scene/instancing.hpp"
#include "util/file.hpp"
#include "util/xml_escape.hpp"

namespace wp {
namespace {

// ---- Text ------------------------------------------------------------------

// The shortest text that reads back as the same double (0.7, not
// 0.69999999999999996); Mitsuba rounds it to its own precision (float32 in
// the scalar_rgb variant) when it parses. -0 is written 0.
std::string number(double value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, value + 0.0);
    return std::string(text, result.ptr);
}

std::string triple(const glm::dvec3& v) {
    return number(v.x) + ", " + number(v.y) + ", " + number(v.z);
}

// XML comments may hold anything but "--" (and must not end in "-") and the
// control characters XML forbids everywhere; a line break would only make
// the comment longer than its line.
std::string xml_comment(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '-' && !out.empty() && out.back() == '-')
            out += ' ';
        out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
    }
    if (!out.empty() && out.back() == '-')
        out += ' ';
    return "<!-- " + out + " -->";
}

// A material name as part of a file name: ASCII letters and digits, the rest
// (spaces, slashes, any other byte) as '_'; at most 40 characters.
std::string file_name_part(const std::string& name) {
    std::string out;
    for (char c : name.substr(0, 40)) {
        const bool plain =
            (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        out += plain ? c : '_';
    }
    return out.empty() ? "unnamed" : out;
}

// ---- PLY -------------------------------------------------------------------

void append_le32(std::vector<unsigned char>& out, std::uint32_t bits) {
    for (int shift = 0; shift < 32; shift += 8)
        out.push_back(static_cast<unsigned char>(bits >> shift));
}

void append_float(std::vector<unsigned char>& out, double value) {
    // The same rounding as the device scene's to_float4: a static_cast.
    const float f = static_cast<float>(value);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    append_le32(out, bits);
}

void append_vector(std::vector<unsigned char>& out, const glm::dvec3& v) {
    append_float(out, v.x);
    append_float(out, v.y);
    append_float(out, v.z);
}

// Binary little-endian PLY, the format Mitsuba's `ply` shape reads natively:
// three vertices per triangle (positions, and normals when asked) and faces
// (0, 1, 2), (3, 4, 5), ... that keep each triangle's winding, hence its
// front face, which is the side Mitsuba's area emitters emit on.
std::vector<unsigned char> encode_ply(const Scene& scene, const TriangleList& list,
                                      const std::vector<std::size_t>& triangles, bool with_normals,
                                      bool with_uvs) {
    const std::size_t vertices = 3 * triangles.size();
    const Material& material = scene.materials[list[triangles.front()].material];
    std::string header = "ply\nformat binary_little_endian 1.0\n";
    header += "comment wavepath export: material '" + file_name_part(material.name) + "', " +
              std::to_string(triangles.size()) + " triangles\n";
    header += "element vertex " + std::to_string(vertices) + "\n";
    header += "property float x\nproperty float y\nproperty float z\n";
    if (with_normals)
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (with_uvs)
        header += "property float u\nproperty float v\n";
    header += "element face " + std::to_string(triangles.size()) + "\n";
    header += "property list uchar int vertex_indices\nend_header\n";

    std::vector<unsigned char> out(header.begin(), header.end());
    out.reserve(out.size() + vertices * (12 + (with_normals ? 12 : 0) + (with_uvs ? 8 : 0)) +
                triangles.size() * 13);
    for (std::size_t index : triangles) {
        const Triangle& t = list[index];
        // A flat triangle among smooth ones keeps its facet: all three vertex
        // normals are the winding normal.
        const glm::dvec3 facet = glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
        const glm::dvec2 corners[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
        for (std::size_t k = 0; k < 3; ++k) {
            append_vector(out, t.v[k]);
            if (with_normals)
                append_vector(out, t.has_normals ? t.normals[k] : facet);
            if (with_uvs) {
                // Without texture coordinates wavepath's textures see the
                // barycentrics (b1, b2), which these corners reproduce.
                const glm::dvec2 uv = t.has_uvs ? t.uvs[k] : corners[k];
                append_float(out, uv.x);
                append_float(out, uv.y);
            }
        }
    }
    for (std::size_t f = 0; f < triangles.size(); ++f) {
        out.push_back(3);
        for (std::uint32_t k = 0; k < 3; ++k)
            append_le32(out, static_cast<std::uint32_t>(3 * f + k));
    }
    return out;
}

// ---- XML -------------------------------------------------------------------

std::string rgb(const std::string& name, const glm::dvec3& value) {
    return "<rgb name=\"" + name + "\" value=\"" + triple(value) + "\"/>";
}

// A shape group's id: its number, then its name as far as a file name may
// hold it (the reader names the group by its id).
std::string group_id(const Scene& scene, std::size_t index) {
    return "group-" + std::to_string(index) + "-" + file_name_part(scene.shape_groups[index].name);
}

std::string material_id(std::size_t index) {
    return "material-" + std::to_string(index);
}

// A texture as Mitsuba's plugin of the same name, for parameter `name`.
std::string texture_xml(const Texture& t, const std::string& name, const std::string& in) {
    std::string x =
        "<texture type=\"" + std::string(texture_kind_name(t.kind)) + "\" name=\"" + name + "\">\n";
    if (t.kind == TextureKind::Bitmap) {
        x += in + "    <string name=\"filename\" value=\"" +
             xml_escape(std::filesystem::absolute(t.path).string()) + "\"/>\n";
        x += in + "    <string name=\"filter_type\" value=\"" + texture_filter_name(t.filter) +
             "\"/>\n";
        x += in + "    <string name=\"wrap_mode\" value=\"" + texture_wrap_name(t.wrap) + "\"/>\n";
        x += in + "    <boolean name=\"raw\" value=\"" + (t.raw ? "true" : "false") + "\"/>\n";
    } else {
        x += in + "    " + rgb("color0", t.color0) + "\n";
        x += in + "    " + rgb("color1", t.color1) + "\n";
    }
    // (u, v) -> (to_u . (u, v, 1), to_v . (u, v, 1)) as a 4x4 matrix on (u, v, 0, 1).
    x += in + "    <transform name=\"to_uv\"><matrix value=\"" + number(t.to_u.x) + " " +
         number(t.to_u.y) + " 0 " + number(t.to_u.z) + " " + number(t.to_v.x) + " " +
         number(t.to_v.y) + " 0 " + number(t.to_v.z) + " 0 0 1 0 0 0 0 1\"/></transform>\n";
    return x + in + "</texture>";
}

// A colour parameter: its constant, or its texture.
std::string colour_xml(const Scene& scene, const std::string& name, const glm::dvec3& value,
                       std::uint32_t texture, const std::string& in) {
    return texture ? texture_xml(scene.textures[texture - 1], name, in) : rgb(name, value);
}

// A rough material's distribution and roughness, as Mitsuba's parameters.
std::string roughness_xml(const Scene& scene, const Material& m, const std::string& in) {
    auto alpha = [&](const char* name, double value, std::uint32_t texture) {
        return texture
                   ? texture_xml(scene.textures[texture - 1], name, in + "    ")
                   : "<float name=\"" + std::string(name) + "\" value=\"" + number(value) + "\"/>";
    };
    return "    <string name=\"distribution\" value=\"" +
           std::string(m.distribution == MicrofacetDistribution::Ggx ? "ggx" : "beckmann") +
           "\"/>\n" + in + "    " + alpha("alpha_u", m.alpha_u, m.alpha_u_texture) + "\n" + in +
           "    " + alpha("alpha_v", m.alpha_v, m.alpha_v_texture) + "\n";
}

// A material's BSDF. wavepath's diffuse and mirror surfaces reflect alike on
// both sides (kernels/shade.cl flips the normal to the side the ray came
// from); Mitsuba's reflect on the front only unless wrapped in `twosided`.
std::string bsdf(const Scene& scene, const Material& m, std::size_t index) {
    const std::string in = "    ";
    std::string inner;
    const auto colour = [&](const std::string& name, const glm::dvec3& value, std::uint32_t texture,
                            const std::string& indent) {
        return colour_xml(scene, name, value, texture, indent);
    };
    switch (m.kind) {
    case MaterialKind::Diffuse:
        inner = in + "    <bsdf type=\"diffuse\">\n" + in + "        " +
                colour("reflectance", m.reflectance, m.reflectance_texture, in + "        ") +
                "\n" + in + "    </bsdf>\n";
        break;
    case MaterialKind::Mirror:
        // Material "none": the perfect mirror (reflectance 1 at every angle,
        // no Fresnel term), scaled by wavepath's reflectance.
        inner = in + "    <bsdf type=\"conductor\">\n" + in +
                "        <string name=\"material\" value=\"none\"/>\n" + in + "        " +
                rgb("specular_reflectance", m.reflectance) + "\n" + in + "    </bsdf>\n";
        break;
    case MaterialKind::Conductor:
    case MaterialKind::RoughConductor: {
        // eta and k as the RGB values wavepath renders with (a named metal's
        // too: Mitsuba's own spectral data would differ a little in colour).
        const bool rough = m.kind == MaterialKind::RoughConductor;
        inner = in + "    <bsdf type=\"" + std::string(material_kind_name(m.kind)) + "\">\n";
        inner += in + "        " + rgb("eta", m.eta) + "\n";
        inner += in + "        " + rgb("k", m.k) + "\n";
        inner +=
            in + "        " +
            colour("specular_reflectance", m.reflectance, m.reflectance_texture, in + "        ") +
            "\n";
        if (rough)
            inner += in + "    " + roughness_xml(scene, m, in + "    ");
        inner += in + "    </bsdf>\n";
        break;
    }
    case MaterialKind::Plastic:
    case MaterialKind::RoughPlastic:
        inner = in + "    <bsdf type=\"" + std::string(material_kind_name(m.kind)) + "\">\n";
        // Mitsuba's roughplastic takes `alpha` alone (it refuses alpha_u and
        // alpha_v); wavepath's are equal for it (validate.cpp).
        if (m.kind == MaterialKind::RoughPlastic)
            inner +=
                in + "        <string name=\"distribution\" value=\"" +
                std::string(m.distribution == MicrofacetDistribution::Ggx ? "ggx" : "beckmann") +
                "\"/>\n" + in + "        <float name=\"alpha\" value=\"" + number(m.alpha_u) +
                "\"/>\n";
        inner += in + "        <float name=\"int_ior\" value=\"" + number(m.int_ior) + "\"/>\n";
        inner += in + "        <float name=\"ext_ior\" value=\"" + number(m.ext_ior) + "\"/>\n";
        inner +=
            in + "        " +
            colour("diffuse_reflectance", m.reflectance, m.reflectance_texture, in + "        ") +
            "\n";
        inner += in + "        " +
                 colour("specular_reflectance", m.specular, m.specular_texture, in + "        ") +
                 "\n";
        inner += in + "        <boolean name=\"nonlinear\" value=\"" +
                 (m.nonlinear ? "true" : "false") + "\"/>\n";
        inner += in + "    </bsdf>\n";
        break;
    case MaterialKind::Dielectric:
    case MaterialKind::ThinDielectric:
    case MaterialKind::RoughDielectric:
        // Not twosided: a dielectric has two sides of its own (Mitsuba refuses
        // to wrap a BSDF that transmits), the front one outside.
        return in + xml_comment("material '" + m.name + "'") + "\n" + in + "<bsdf type=\"" +
               material_kind_name(m.kind) + "\" id=\"" + material_id(index) + "\">\n" +
               (m.kind == MaterialKind::RoughDielectric ? in + roughness_xml(scene, m, in) : "") +
               in + "    <float name=\"int_ior\" value=\"" + number(m.int_ior) + "\"/>\n" + in +
               "    <float name=\"ext_ior\" value=\"" + number(m.ext_ior) + "\"/>\n" + in + "    " +
               colour("specular_reflectance", m.reflectance, m.reflectance_texture, in + "    ") +
               "\n" + in + "    " +
               colour("specular_transmittance", m.transmittance, m.transmittance_texture,
                      in + "    ") +
               "\n" + in + "</bsdf>\n";
    case MaterialKind::Emitter:
        // Reflects nothing, on either side: black, and one-sided will do.
        return in + xml_comment("material '" + m.name + "' (emitter: reflects nothing)") + "\n" +
               in + "<bsdf type=\"diffuse\" id=\"" + material_id(index) + "\">\n" + in + "    " +
               rgb("reflectance", glm::dvec3(0.0)) + "\n" + in + "</bsdf>\n";
    }
    return in + xml_comment("material '" + m.name + "'") + "\n" + in +
           "<bsdf type=\"twosided\" id=\"" + material_id(index) + "\">\n" + inner + in +
           "</bsdf>\n";
}

// wavepath emits from the front face (the winding normal's side) only, as
// Mitsuba's `area` emitter does from the side its surface normal faces.
std::string area_emitter(const Material& m) {
    if (!m.is_emissive())
        return {};
    return "        <emitter type=\"area\">\n            " + rgb("radiance", m.emission) +
           "\n        </emitter>\n";
}

std::string integrator(const Scene& scene) {
    // wavepath ends paths by Russian roulette and cuts them at 1024 bounces as
    // a guard against lossless mirror corridors; no path reaches the cap in a
    // scene that absorbs anything. Mitsuba's `path` with no depth limit (-1)
    // and its own roulette (from depth rr_depth = 5) estimates the same
    // integral: both are unbiased, so the images agree in expectation. A
    // Mitsuba file's own max_depth and rr_depth (Scene::max_depth) go back
    // as they came.
    std::string text = "    <integrator type=\"path\">\n";
    text +=
        "        <integer name=\"max_depth\" value=\"" + std::to_string(scene.max_depth) + "\"/>\n";
    if (scene.rr_depth > 0)
        text += "        <integer name=\"rr_depth\" value=\"" + std::to_string(scene.rr_depth) +
                "\"/>\n";
    if (scene.hide_emitters)
        text += "        <boolean name=\"hide_emitters\" value=\"true\"/>\n";
    text += "    </integrator>\n";
    return text;
}

// A point, spot, directional, constant or envmap emitter as Mitsuba 3's plugin of
// that name, which the XML reader reads back to the same Emitter. A spot is
// placed by a lookat along its axis (its roll changes nothing).
std::string scene_emitter(const Emitter& e) {
    std::string s = std::string("    <emitter type=\"") + emitter_kind_name(e.kind) + "\">\n";
    switch (e.kind) {
    case EmitterKind::Point:
        s += "        <point name=\"position\" value=\"" + triple(e.position) + "\"/>\n";
        s += "        " + rgb("intensity", e.value) + "\n";
        break;
    case EmitterKind::Spot: {
        const glm::dvec3 up =
            std::abs(e.direction.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
        s += "        " + rgb("intensity", e.value) + "\n";
        s += "        <float name=\"cutoff_angle\" value=\"" + number(e.cutoff_angle) + "\"/>\n";
        s += "        <float name=\"beam_width\" value=\"" + number(e.beam_width) + "\"/>\n";
        s += "        <transform name=\"to_world\">\n";
        s += "            <lookat origin=\"" + triple(e.position) + "\" target=\"" +
             triple(e.position + e.direction) + "\" up=\"" + triple(up) + "\"/>\n";
        s += "        </transform>\n";
        break;
    }
    case EmitterKind::Directional:
        s += "        <vector name=\"direction\" value=\"" + triple(e.direction) + "\"/>\n";
        s += "        " + rgb("irradiance", e.value) + "\n";
        break;
    case EmitterKind::Constant:
        s += "        " + rgb("radiance", e.value) + "\n";
        break;
    case EmitterKind::Envmap: {
        // The image by its absolute path, as a bitmap texture's; the
        // rotation as its matrix, row by row.
        s += "        <string name=\"filename\" value=\"" +
             xml_escape(std::filesystem::absolute(e.path).string()) + "\"/>\n";
        s += "        <float name=\"scale\" value=\"" + number(e.value.x) + "\"/>\n";
        if (e.to_world != glm::dmat3(1.0)) {
            std::string m;
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c)
                    m += (m.empty() ? "" : " ") + number(r < 3 && c < 3 ? e.to_world[c][r]
                                                         : r == c       ? 1.0
                                                                        : 0.0);
            s += "        <transform name=\"to_world\">\n";
            s += "            <matrix value=\"" + m + "\"/>\n";
            s += "        </transform>\n";
        }
        break;
    }
    }
    return s + "    </emitter>\n";
}

std::string sensor(const Scene& scene, const MitsubaExportOptions& options) {
    const MitsubaCamera c = mitsuba_camera(scene);
    std::string s =
        "    " +
        xml_comment("wavepath's camera: vertical fov " + number(scene.camera.vertical_fov_degrees) +
                    " degrees; " + std::to_string(scene.camera.width) + "x" +
                    std::to_string(scene.camera.height) + " pixels") +
        "\n";
    // A lens is Mitsuba's thinlens sensor: the same aperture disk in the
    // plane of the eye and the same plane of focus (kernels/camera.h).
    const bool lens = scene.camera.aperture_radius > 0.0;
    s += std::string("    <sensor type=\"") + (lens ? "thinlens" : "perspective") + "\">\n";
    s += "        <string name=\"fov_axis\" value=\"x\"/>\n";
    s += "        <float name=\"fov\" value=\"" + number(c.fov_x_degrees) + "\"/>\n";
    if (lens) {
        s += "        <float name=\"aperture_radius\" value=\"" +
             number(scene.camera.aperture_radius) + "\"/>\n";
        s += "        <float name=\"focus_distance\" value=\"" +
             number(scene.camera.focus_distance) + "\"/>\n";
    }
    s += "        <float name=\"near_clip\" value=\"" + number(c.near_clip) + "\"/>\n";
    s += "        <float name=\"far_clip\" value=\"" + number(c.far_clip) + "\"/>\n";
    s += "        <transform name=\"to_world\">\n";
    s += "            <lookat origin=\"" + triple(c.origin) + "\" target=\"" + triple(c.target) +
         "\" up=\"" + triple(c.up) + "\"/>\n";
    s += "        </transform>\n";
    s += "        <sampler type=\"independent\">\n";
    s += "            <integer name=\"sample_count\" value=\"" +
         std::to_string(options.sample_count) + "\"/>\n";
    s += "        </sampler>\n";
    // The same pixel filter: wavepath draws each sample's position from it
    // (kernels/camera.h), Mitsuba splats with its weights; both converge to
    // the filtered image.
    s += "        <film type=\"hdrfilm\">\n";
    s += "            <integer name=\"width\" value=\"" + std::to_string(scene.camera.width) +
         "\"/>\n";
    s += "            <integer name=\"height\" value=\"" + std::to_string(scene.camera.height) +
         "\"/>\n";
    s += "            <string name=\"pixel_format\" value=\"rgb\"/>\n";
    switch (scene.camera.filter) {
    case FilterKind::Box:
        s += "            <rfilter type=\"box\"/>\n";
        break;
    case FilterKind::Tent:
        s += "            <rfilter type=\"tent\">\n"
             "                <float name=\"radius\" value=\"" +
             number(scene.camera.filter_radius) + "\"/>\n            </rfilter>\n";
        break;
    case FilterKind::Gaussian:
        s += "            <rfilter type=\"gaussian\">\n"
             "                <float name=\"stddev\" value=\"" +
             number(scene.camera.filter_stddev) + "\"/>\n            </rfilter>\n";
        break;
    }
    s += "        </film>\n";
    s += "    </sensor>\n";
    return s;
}

} // namespace

MitsubaCamera mitsuba_camera(const Scene& scene) {
    const Camera& c = scene.camera;
    // wavepath's camera frame, as device_scene.cpp builds it.
    const glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::dvec3 up = glm::cross(right, forward);
    const double half_height = std::tan(0.5 * c.vertical_fov_degrees * M_PI / 180.0);
    const double aspect = static_cast<double>(c.width) / static_cast<double>(c.height);

    double farthest = 0.0; // from the eye, over the whole scene
    for (const Triangle& t : scene.triangles)
        for (const glm::dvec3& v : t.v)
            farthest = std::max(farthest, glm::length(v - c.eye));
    for (const Sphere& s : scene.spheres)
        farthest = std::max(farthest, glm::length(s.center - c.eye) + s.radius);
    for (const Instance& instance : scene.instances) {
        const DoubleBox b =
            mapped_box(group_box(scene.shape_groups[instance.group]), instance.to_world);
        if (!b.empty())
            for (int corner = 0; corner < 8; ++corner)
                farthest =
                    std::max(farthest, glm::length(glm::dvec3(corner & 1 ? b.upper.x : b.lower.x,
                                                              corner & 2 ? b.upper.y : b.lower.y,
                                                              corner & 4 ? b.upper.z : b.lower.z) -
                                                   c.eye));
    }

    MitsubaCamera m;
    m.origin = c.eye;
    // Mitsuba takes target - origin in its own precision; a target at least
    // as far from the origin as the origin is from 0 keeps that difference
    // as accurate as the numbers themselves.
    m.target =
        c.eye + forward * std::max({glm::length(c.look_at - c.eye), glm::length(c.eye), 1.0});
    m.up = up;
    m.fov_x_degrees = 2.0 * std::atan(half_height * aspect) * 180.0 / M_PI;
    // Mitsuba's default planes (0.01 and 10^4) would cut scenes in small or
    // large units; these keep everything, with Mitsuba's ratio of 10^6.
    m.far_clip = 2.0 * std::max(farthest, 1e-30);
    m.near_clip = 1e-6 * m.far_clip;
    return m;
}

MitsubaExport export_mitsuba(const Scene& scene, const std::string& mesh_prefix,
                             const MitsubaExportOptions& options) {
    MitsubaExport out;

    // The triangles of each material, in the list's order: one PLY file
    // each, for the scene's own triangles (group -1) and each shape group's.
    std::size_t smooth_triangles = 0;
    auto add_meshes = [&](const TriangleList& list, int group) {
        std::map<std::uint32_t, std::vector<std::size_t>> by_material;
        for (std::size_t i = 0; i < list.size(); ++i)
            by_material[list[i].material].push_back(i);
        for (auto& [material_index, triangles] : by_material) {
            const Material& material = scene.materials[material_index];
            const std::size_t smooth = static_cast<std::size_t>(
                std::count_if(triangles.begin(), triangles.end(),
                              [&](std::size_t i) { return list[i].has_normals; }));
            // Mitsuba's area emitter emits on the side of the interpolated normal
            // where a mesh has vertex normals, wavepath's on the winding's side.
            // An emissive material's triangles are therefore written flat; for an
            // emitter, which reflects nothing, that changes nothing.
            const bool with_normals = smooth > 0 && !material.is_emissive();
            if (smooth > 0 && material.is_emissive() && material.kind != MaterialKind::Emitter)
                out.warnings.push_back("material '" + material.name +
                                       "': " + std::to_string(smooth) +
                                       " triangles with shading normals are emissive; they are "
                                       "exported flat, since Mitsuba would emit by the normals");
            if (with_normals)
                smooth_triangles += smooth;

            MitsubaMesh mesh;
            mesh.file_name = mesh_prefix + "-" + std::to_string(out.meshes.size()) + "-" +
                             file_name_part(material.name) + ".ply";
            mesh.material = material_index;
            mesh.group = group;
            mesh.triangle_count = triangles.size();
            mesh.has_normals = with_normals;
            mesh.ply = encode_ply(scene, list, triangles, with_normals, !scene.textures.empty());
            out.meshes.push_back(std::move(mesh));
        }
    };
    add_meshes(scene.triangles, -1);
    for (std::size_t g = 0; g < scene.shape_groups.size(); ++g)
        add_meshes(scene.shape_groups[g].triangles, static_cast<int>(g));
    if (smooth_triangles > 0)
        out.warnings.push_back(
            std::to_string(smooth_triangles) +
            " triangles have shading normals: Mitsuba interpolates them as wavepath does, but "
            "without wavepath's shadow-terminator fix (docs/meshes.md), so the images differ "
            "slightly where the normals bend away from the facets");

    std::string& x = out.xml;
    x = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
    x += xml_comment("Written by wavepath export-mitsuba from " + scene.source +
                     "; render with Mitsuba 3 (docs/mitsuba-export.md)") +
         "\n";
    x += "<scene version=\"3.0.0\">\n";
    x += integrator(scene);
    x += sensor(scene, options);
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        x += bsdf(scene, scene.materials[i], i);
    auto ply_shape = [&](const MitsubaMesh& mesh, const std::string& indent) {
        const Material& material = scene.materials[mesh.material];
        x += indent + "<shape type=\"ply\">\n";
        x += indent + "    <string name=\"filename\" value=\"" + xml_escape(mesh.file_name) +
             "\"/>\n";
        // Without vertex normals Mitsuba would compute smooth ones; wavepath
        // shades these triangles by their facets.
        x += indent + "    <boolean name=\"face_normals\" value=\"" +
             (mesh.has_normals ? "false" : "true") + "\"/>\n";
        x += indent + "    <ref id=\"" + material_id(mesh.material) + "\"/>\n";
        x += area_emitter(material); // never inside a group: groups hold no emitters
        x += indent + "</shape>\n";
    };
    for (const MitsubaMesh& mesh : out.meshes)
        if (mesh.group < 0)
            ply_shape(mesh, "    ");
    // Shape groups, each with its meshes, and their instances by a matrix
    // written row by row, as Mitsuba's <matrix> reads it.
    for (std::size_t g = 0; g < scene.shape_groups.size(); ++g) {
        x += "    <shape type=\"shapegroup\" id=\"" + xml_escape(group_id(scene, g)) + "\">\n";
        for (const MitsubaMesh& mesh : out.meshes)
            if (mesh.group == static_cast<int>(g))
                ply_shape(mesh, "        ");
        x += "    </shape>\n";
    }
    for (const Instance& instance : scene.instances) {
        x += "    <shape type=\"instance\">\n";
        x += "        <ref id=\"" + xml_escape(group_id(scene, instance.group)) + "\"/>\n";
        std::string rows;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                if (!rows.empty())
                    rows += ' ';
                rows += number(instance.to_world[c][r]);
            }
        x += "        <transform name=\"to_world\"><matrix value=\"" + rows + "\"/></transform>\n";
        x += "    </shape>\n";
    }
    for (const Sphere& s : scene.spheres) {
        x += "    <shape type=\"sphere\">\n";
        x += "        <point name=\"center\" value=\"" + triple(s.center) + "\"/>\n";
        x += "        <float name=\"radius\" value=\"" + number(s.radius) + "\"/>\n";
        x += "        <ref id=\"" + material_id(s.material) + "\"/>\n";
        x += area_emitter(scene.materials[s.material]);
        x += "    </shape>\n";
    }
    for (const Emitter& e : scene.emitters)
        x += scene_emitter(e);
    x += "</scene>\n";
    return out;
}

std::vector<std::filesystem::path> mitsuba_mesh_paths(const MitsubaExport& exported,
                                                      const std::filesystem::path& xml_path) {
    std::vector<std::filesystem::path> paths;
    for (const MitsubaMesh& mesh : exported.meshes)
        paths.push_back(xml_path.parent_path() / mesh.file_name);
    return paths;
}

void write_mitsuba(const MitsubaExport& exported, const std::filesystem::path& xml_path) {
    const std::vector<std::filesystem::path> paths = mitsuba_mesh_paths(exported, xml_path);
    for (std::size_t i = 0; i < paths.size(); ++i)
        write_bytes_atomically(paths[i], exported.meshes[i].ply.data(),
                               exported.meshes[i].ply.size());
    write_bytes_atomically(xml_path, exported.xml.data(), exported.xml.size());
}

} // namespace wp
