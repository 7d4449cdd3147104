#include "render/device_scene.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace wp {
namespace {

wp_float4 to_float4(const glm::dvec3& v, double w = 0.0) {
    wp_float4 r;
    r.s[0] = static_cast<float>(v.x);
    r.s[1] = static_cast<float>(v.y);
    r.s[2] = static_cast<float>(v.z);
    r.s[3] = static_cast<float>(w);
    return r;
}

std::string flag(const char* name, bool on) {
    return std::string("-D ") + name + (on ? "=1" : "=0");
}

// The kernels' material constants (wp_shared.h) are the host's MaterialKind
// values: flatten_scene copies the kind across as it is.
static_assert(static_cast<wp_uint>(MaterialKind::Diffuse) == WP_MATERIAL_DIFFUSE);
static_assert(static_cast<wp_uint>(MaterialKind::Mirror) == WP_MATERIAL_MIRROR);
static_assert(static_cast<wp_uint>(MaterialKind::Emitter) == WP_MATERIAL_EMITTER);

} // namespace

// Appends `word` to a space-separated list.
static void append_word(std::string& list, const std::string& word) {
    if (!list.empty())
        list += ' ';
    list += word;
}

std::string SceneFeatures::build_options() const {
    std::string options;
#define WP_FEATURE_FLAG(member, kernel_switch) append_word(options, flag(#kernel_switch, member));
    WP_SCENE_FEATURES(WP_FEATURE_FLAG)
#undef WP_FEATURE_FLAG
    if (fixed_counts)
        options += " -D WP_TRIANGLE_COUNT=" + std::to_string(triangle_count) +
                   " -D WP_SPHERE_COUNT=" + std::to_string(sphere_count);
    return options;
}

std::string SceneFeatures::describe() const {
    std::string out;
#define WP_FEATURE_NAME(member, kernel_switch)                                                     \
    if (member)                                                                                    \
        append_word(out, #member);
    WP_SCENE_FEATURES(WP_FEATURE_NAME)
#undef WP_FEATURE_NAME
    if (fixed_counts)
        out += "; counts " + std::to_string(triangle_count) + "+" + std::to_string(sphere_count);
    return out;
}

SceneFeatures analyse_features(const Scene& scene, std::uint32_t max_fixed_count_primitives) {
    SceneFeatures f;
    f.triangles = !scene.triangles.empty();
    f.spheres = !scene.spheres.empty();
    auto uses = [&](MaterialKind kind) {
        for (const Triangle& t : scene.triangles)
            if (scene.materials[t.material].kind == kind)
                return true;
        for (const Sphere& s : scene.spheres)
            if (scene.materials[s.material].kind == kind)
                return true;
        return false;
    };
    f.diffuse = uses(MaterialKind::Diffuse);
    f.mirror = uses(MaterialKind::Mirror);
    f.lights = false;
    for (const Triangle& t : scene.triangles)
        f.lights = f.lights || scene.materials[t.material].is_emissive();
    const std::size_t primitives = scene.triangles.size() + scene.spheres.size();
    f.fixed_counts = primitives <= max_fixed_count_primitives;
    if (f.fixed_counts) {
        f.triangle_count = static_cast<std::uint32_t>(scene.triangles.size());
        f.sphere_count = static_cast<std::uint32_t>(scene.spheres.size());
    }
    return f;
}

DeviceScene flatten_scene(const Scene& scene) {
    DeviceScene out;
    out.width = scene.camera.width;
    out.height = scene.camera.height;

    for (const Material& m : scene.materials) {
        WpMaterial w{};
        w.reflectance = to_float4(m.reflectance);
        w.emission = to_float4(m.emission);
        w.kind = static_cast<wp_uint>(m.kind);
        out.materials.push_back(w);
    }

    std::vector<double> areas;
    double total_area = 0.0;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        WpTriangle w{};
        w.v0 = to_float4(t.v[0]);
        w.v1 = to_float4(t.v[1]);
        w.v2 = to_float4(t.v[2]);
        w.material = t.material;
        out.triangles.push_back(w);
        if (scene.materials[t.material].is_emissive()) {
            double area = 0.5 * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
            WpLight light{};
            light.triangle = static_cast<wp_uint>(i);
            out.lights.push_back(light);
            areas.push_back(area);
            total_area += area;
        }
    }
    double running = 0.0;
    for (std::size_t i = 0; i < out.lights.size(); ++i) {
        running += areas[i];
        out.lights[i].cdf = static_cast<float>(running / total_area);
    }
    if (!out.lights.empty())
        out.lights.back().cdf = 1.0f; // never let rounding leave u in no bin
    out.light_area = static_cast<float>(total_area);

    for (const Sphere& s : scene.spheres) {
        WpSphere w{};
        w.center_radius = to_float4(s.center, s.radius);
        w.material = s.material;
        out.spheres.push_back(w);
    }

    const Camera& c = scene.camera;
    glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
    glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    glm::dvec3 up = glm::cross(right, forward);
    double half_height = std::tan(0.5 * c.vertical_fov_degrees * M_PI / 180.0);
    double aspect = static_cast<double>(c.width) / static_cast<double>(c.height);
    out.camera.eye = to_float4(c.eye);
    out.camera.forward = to_float4(forward);
    out.camera.right = to_float4(right * (half_height * aspect));
    out.camera.up = to_float4(up * half_height);
    return out;
}

} // namespace wp
