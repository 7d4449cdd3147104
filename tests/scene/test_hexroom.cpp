// The reference scene, scenes/hexroom.json, against /work/shared/specs/hexroom.md.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/validate.hpp"

namespace {

const std::string kHexroom = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/hexroom.json";

glm::dvec3 normal_of(const wp::Triangle& t) {
    return glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
}
glm::dvec3 centroid_of(const wp::Triangle& t) {
    return (t.v[0] + t.v[1] + t.v[2]) / 3.0;
}
double area_of(const wp::Triangle& t) {
    return 0.5 * glm::length(normal_of(t));
}

const wp::Material& material_of(const wp::Scene& s, std::uint32_t index) {
    REQUIRE(index < s.materials.size());
    return s.materials[index];
}

} // namespace

TEST_CASE("hexroom: loads with the spec's counts", "[scene][hexroom]") {
    const wp::Scene s = wp::load_scene(kHexroom);
    CHECK(s.source == kHexroom);
    CHECK(s.triangles.size() == 26); // 6 walls x 2 + floor 4 + ceiling 4 + tetra 4 + light 2
    CHECK(s.spheres.size() == 2);
    CHECK(s.materials.size() == 12);
    CHECK(s.warnings.empty());
    CHECK_NOTHROW(wp::validate_scene(s));

    std::map<std::string, int> per_material;
    for (const auto& t : s.triangles)
        ++per_material[material_of(s, t.material).name];
    const std::map<std::string, int> expected{{"back_left_wall", 2},  {"left_wall", 2},
                                              {"front_left_wall", 2}, {"front_right_wall", 2},
                                              {"right_wall", 2},      {"back_right_wall", 2},
                                              {"floor", 4},           {"ceiling", 4},
                                              {"tetrahedron", 4},     {"light", 2}};
    CHECK(per_material == expected);
}

TEST_CASE("hexroom: camera", "[scene][hexroom]") {
    const wp::Camera c = wp::load_scene(kHexroom).camera;
    CHECK(c.eye == glm::dvec3(-1, 0, 0));
    CHECK(c.look_at == glm::dvec3(0, 0, 0));
    CHECK(c.up == glm::dvec3(0, 0, 1));
    CHECK(c.vertical_fov_degrees == 90.0);
    CHECK(c.width == 800);
    CHECK(c.height == 800);
}

TEST_CASE("hexroom: materials match the spec table", "[scene][hexroom]") {
    const wp::Scene s = wp::load_scene(kHexroom);
    struct Row {
        const char* name;
        wp::MaterialKind kind;
        glm::dvec3 rho;
    };
    using K = wp::MaterialKind;
    const Row rows[] = {
        {"back_left_wall", K::Diffuse, {0.2, 0.7, 0.7}},
        {"left_wall", K::Diffuse, {0.2, 0.7, 0.2}},
        {"front_left_wall", K::Diffuse, {0.2, 0.2, 0.7}},
        {"front_right_wall", K::Mirror, {1, 1, 1}},
        {"right_wall", K::Diffuse, {0.5, 0.2, 0.7}},
        {"back_right_wall", K::Diffuse, {0.7, 0.7, 0.2}},
        {"floor", K::Diffuse, {0.7, 0.7, 0.7}},
        {"ceiling", K::Diffuse, {0.7, 0.7, 0.7}},
        {"mirror_sphere", K::Mirror, {1, 1, 1}},
        {"red_sphere", K::Diffuse, {0.2, 0.02, 0.02}},
        {"tetrahedron", K::Diffuse, {0.6, 0.3, 0.48}},
        {"light", K::Emitter, {0, 0, 0}},
    };
    for (const Row& r : rows) {
        INFO(r.name);
        const wp::Material* m = nullptr;
        for (const auto& candidate : s.materials)
            if (candidate.name == r.name)
                m = &candidate;
        REQUIRE(m != nullptr);
        CHECK(m->kind == r.kind);
        CHECK(m->reflectance == r.rho);
        if (r.kind == K::Emitter)
            CHECK(m->emission == glm::dvec3(100, 100, 100));
        else
            CHECK_FALSE(m->is_emissive());
    }
}

TEST_CASE("hexroom: room surfaces face into the room", "[scene][hexroom]") {
    const wp::Scene s = wp::load_scene(kHexroom);
    const glm::dvec3 room_centre(5, 0, 0);
    double floor_area = 0.0;
    double ceiling_area = 0.0;
    int checked = 0;
    for (const auto& t : s.triangles) {
        const std::string& name = material_of(s, t.material).name;
        if (name == "tetrahedron" || name == "light")
            continue;
        INFO(name);
        CHECK(glm::dot(normal_of(t), room_centre - centroid_of(t)) > 0.0);
        ++checked;
        if (name == "floor") {
            CHECK(glm::normalize(normal_of(t)) == glm::dvec3(0, 0, 1));
            for (const auto& v : t.v)
                CHECK(v.z == -5.0);
            floor_area += area_of(t);
        } else if (name == "ceiling") {
            CHECK(glm::normalize(normal_of(t)) == glm::dvec3(0, 0, -1));
            for (const auto& v : t.v)
                CHECK(v.z == 5.0);
            ceiling_area += area_of(t);
        } else {
            CHECK(normal_of(t).z == 0.0); // walls are vertical
            CHECK(area_of(t) > 0.0);
        }
    }
    CHECK(checked == 20);
    // Hexagon ABCDEF: width 16 at y = 0, 10 at y = +-6, so area 2 * 6 * (16 + 10) / 2.
    CHECK(floor_area == Approx(156.0).epsilon(1e-12));
    CHECK(ceiling_area == Approx(156.0).epsilon(1e-12));
}

TEST_CASE("hexroom: the light faces down with area 4", "[scene][hexroom]") {
    const wp::Scene s = wp::load_scene(kHexroom);
    double area = 0.0;
    int n = 0;
    for (const auto& t : s.triangles) {
        if (material_of(s, t.material).name != "light")
            continue;
        ++n;
        CHECK(glm::normalize(normal_of(t)) == glm::dvec3(0, 0, -1));
        for (const auto& v : t.v) {
            CHECK(v.z == 4.99);
            CHECK((v.x == 4.0 || v.x == 6.0));
            CHECK((v.y == -1.0 || v.y == 1.0));
        }
        area += area_of(t);
    }
    CHECK(n == 2);
    CHECK(area == Approx(4.0).epsilon(1e-12));
}

TEST_CASE("hexroom: regular tetrahedron with outward faces", "[scene][hexroom]") {
    const wp::Scene s = wp::load_scene(kHexroom);
    const glm::dvec3 v0(9.309401076758503, -3.5, -5);
    const glm::dvec3 v1(5.845299461620749, -1.5, -5);
    const glm::dvec3 v2(5.845299461620749, -5.5, -5);
    const glm::dvec3 v3(7, -3.5, -1.734013676289096);
    const glm::dvec3 centre = (v0 + v1 + v2 + v3) / 4.0;
    int n = 0;
    for (const auto& t : s.triangles) {
        if (material_of(s, t.material).name != "tetrahedron")
            continue;
        ++n;
        CHECK(glm::dot(normal_of(t), centroid_of(t) - centre) > 0.0);
        for (int i = 0; i < 3; ++i) {
            const auto& a = t.v[static_cast<std::size_t>(i)];
            const auto& b = t.v[static_cast<std::size_t>((i + 1) % 3)];
            CHECK(std::abs(glm::length(b - a) - 4.0) < 1e-9);
            // Every vertex is one of the spec's, to full precision.
            CHECK((a == v0 || a == v1 || a == v2 || a == v3));
        }
    }
    CHECK(n == 4);
}

TEST_CASE("hexroom: spheres", "[scene][hexroom]") {
    const wp::Scene s = wp::load_scene(kHexroom);
    REQUIRE(s.spheres.size() == 2);
    const auto& mirror = s.spheres[0];
    const auto& red = s.spheres[1];
    CHECK(mirror.center == glm::dvec3(9, 2.5, -3));
    CHECK(mirror.radius == 2.0);
    CHECK(material_of(s, mirror.material).name == "mirror_sphere");
    CHECK(red.center == glm::dvec3(5.5, 0.5, -4.3));
    CHECK(red.radius == 0.7);
    CHECK(material_of(s, red.material).name == "red_sphere");
}
