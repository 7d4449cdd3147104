// What the loader builds from valid input: quads, meshes, warnings, camera forms.
#include <catch2/catch.hpp>

#include <array>
#include <string>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "support/scene_json.hpp"

namespace {

using wp::test::kSceneCamera;

wp::Scene with_shapes(const std::string& shapes, const std::string& camera = kSceneCamera) {
    return wp::parse_scene(wp::test::scene_json(camera, wp::test::kSceneMaterials, shapes),
                           "test.json");
}

glm::dvec3 normal_of(const wp::Triangle& t) {
    return glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
}

} // namespace

TEST_CASE("loader: a quad is split into (v0, v1, v2) and (v0, v2, v3)", "[scene][load]") {
    const glm::dvec3 v0(0, 0, 1), v1(2, 0, 1), v2(2, 3, 1), v3(0, 3, 1);
    const wp::Scene s = with_shapes(
        R"([{"type": "quad", "vertices": [[0, 0, 1], [2, 0, 1], [2, 3, 1], [0, 3, 1]], "material": "mirror"}])");
    REQUIRE(s.triangles.size() == 2);
    CHECK(s.triangles[0].v == std::array<glm::dvec3, 3>{v0, v1, v2});
    CHECK(s.triangles[1].v == std::array<glm::dvec3, 3>{v0, v2, v3});
    for (const auto& t : s.triangles) {
        CHECK(t.material == 1); // materials are numbered in file order
        CHECK(glm::normalize(normal_of(t)) == glm::dvec3(0, 0, 1));
    }
    CHECK(s.warnings.empty());

    SECTION("reversed winding gives the opposite normal") {
        const wp::Scene r = with_shapes(
            R"([{"type": "quad", "vertices": [[0, 3, 1], [2, 3, 1], [2, 0, 1], [0, 0, 1]], "material": "white"}])");
        REQUIRE(r.triangles.size() == 2);
        for (const auto& t : r.triangles)
            CHECK(glm::normalize(normal_of(t)) == glm::dvec3(0, 0, -1));
    }
}

TEST_CASE("loader: quad coplanarity is relative to its size", "[scene][load]") {
    // 1e-8 off the plane of a quad of size ~1.4e2: within 1e-6 relative.
    const wp::Scene s = with_shapes(
        R"([{"type": "quad", "vertices": [[0, 0, 0], [100, 0, 0], [100, 100, 0], [0, 100, 1e-8]], "material": "white"}])");
    CHECK(s.triangles.size() == 2);
    // A tiny quad (side 1e-4) with a relatively large bend is rejected.
    CHECK_THROWS_WITH(
        with_shapes(
            R"([{"type": "quad", "vertices": [[0, 0, 0], [1e-4, 0, 0], [1e-4, 1e-4, 0], [0, 1e-4, 1e-9]], "material": "white"}])"),
        Catch::Contains("/shapes/0/vertices: the 4 corners are not coplanar"));
}

TEST_CASE("loader: zero-area triangles are skipped with a warning", "[scene][load]") {
    SECTION("a collinear triangle") {
        const wp::Scene s = with_shapes(R"([
            {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "white"},
            {"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]], "material": "white"}])");
        CHECK(s.triangles.size() == 1);
        REQUIRE(s.warnings.size() == 1);
        CHECK(s.warnings[0] == "/shapes/1: skipped zero-area triangle");
    }
    SECTION("a sliver below 1e-12 relative") {
        const wp::Scene s = with_shapes(R"([
            {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
            {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [2, 1e-13, 0]], "material": "white"}])");
        CHECK(s.triangles.empty());
        REQUIRE(s.warnings.size() == 1);
        CHECK(s.warnings[0] == "/shapes/1: skipped zero-area triangle");
    }
    SECTION("a tiny but well-shaped triangle is kept") {
        const wp::Scene s = with_shapes(R"([
            {"type": "triangle", "vertices": [[0, 0, 0], [1e-9, 0, 0], [0, 1e-9, 0]], "material": "white"}])");
        CHECK(s.triangles.size() == 1);
        CHECK(s.warnings.empty());
    }
    SECTION("a mesh triangle with a repeated index") {
        const wp::Scene s = with_shapes(R"([
            {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
             "triangles": [[0, 1, 2], [0, 1, 1], [2, 1, 0]], "material": "white"}])");
        CHECK(s.triangles.size() == 2);
        REQUIRE(s.warnings.size() == 1);
        CHECK(s.warnings[0] == "/shapes/0/triangles/1: skipped zero-area triangle");
    }
    SECTION("a quad with a doubled corner keeps its good half") {
        const wp::Scene s = with_shapes(R"([
            {"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 0]], "material": "white"}])");
        CHECK(s.triangles.size() == 1);
        REQUIRE(s.warnings.size() == 1);
        CHECK(s.warnings[0].rfind("/shapes/0: skipped zero-area triangle", 0) == 0);
    }
}

TEST_CASE("loader: meshes keep their index order", "[scene][load]") {
    const wp::Scene s = with_shapes(R"([
        {"type": "mesh", "name": "two", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
         "triangles": [[0, 1, 2], [0, 2, 3]], "material": "white"}])");
    REQUIRE(s.triangles.size() == 2);
    CHECK(s.triangles[1].v[0] == glm::dvec3(0, 0, 0));
    CHECK(s.triangles[1].v[1] == glm::dvec3(1, 1, 0));
    CHECK(s.triangles[1].v[2] == glm::dvec3(0, 1, 0));
}

TEST_CASE("loader: camera forms", "[scene][load]") {
    const std::string shapes =
        R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "mirror"}])";
    SECTION("direction instead of look_at") {
        const wp::Scene s = with_shapes(
            shapes,
            R"({"eye": [1, 2, 3], "direction": [0, 2, 0], "up": [0, 0, 1], "fov": 45.5, "resolution": [640, 480]})");
        CHECK(s.camera.eye == glm::dvec3(1, 2, 3));
        CHECK(s.camera.look_at == glm::dvec3(1, 4, 3));
        CHECK(s.camera.vertical_fov_degrees == 45.5);
        CHECK(s.camera.width == 640);
        CHECK(s.camera.height == 480);
    }
    SECTION("integral floats are integers") {
        const wp::Scene s = with_shapes(
            shapes,
            R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [800.0, 16384]})");
        CHECK(s.camera.width == 800);
        CHECK(s.camera.height == 16384);
    }
    SECTION("far from the origin and tiny scales are fine") {
        const wp::Scene s = with_shapes(
            R"([{"type": "sphere", "center": [1e5, -1e5, 1e5], "radius": 1e-4, "material": "white"}])",
            R"({"eye": [100000, -100000, 99999], "look_at": [100000, -100000, 100000], "up": [0, 1, 0], "fov": 90, "resolution": [8, 8]})");
        CHECK(s.spheres.size() == 1);
    }
}

TEST_CASE("loader: materials", "[scene][load]") {
    const wp::Scene s = wp::parse_scene(R"({
        "camera": {"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]},
        "materials": {
            "zeta": {"type": "emitter", "radiance": [1, 2, 3]},
            "alpha": {"type": "diffuse", "reflectance": [0, 0.5, 1], "emission": [4, 5, 6]},
            "dark": {"type": "emitter", "radiance": [0, 0, 0]}},
        "shapes": [{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "alpha"}]})",
                                        "m.json");
    REQUIRE(s.materials.size() == 3);
    CHECK(s.materials[0].name == "zeta");
    CHECK(s.materials[0].kind == wp::MaterialKind::Emitter);
    CHECK(s.materials[0].reflectance == glm::dvec3(0.0));
    CHECK(s.materials[0].emission == glm::dvec3(1, 2, 3));
    CHECK(s.materials[1].name == "alpha");
    CHECK(s.materials[1].kind == wp::MaterialKind::Diffuse);
    CHECK(s.materials[1].emission == glm::dvec3(4, 5, 6));
    CHECK(s.triangles[0].material == 1);
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0] == "/materials/dark/radiance: emitter with zero radiance emits nothing");
}

TEST_CASE("loader: conductors read Mitsuba's parameters and defaults", "[scene][load]") {
    const wp::Scene s = wp::parse_scene(R"({"camera": )" + kSceneCamera + R"(, "materials": {
            "plain": {"type": "conductor"},
            "gold": {"type": "conductor", "material": "Au", "specular_reflectance": [1, 0.5, 1]},
            "given": {"type": "conductor", "eta": [1, 2, 3], "k": [4, 5, 6]},
            "rough": {"type": "roughconductor"},
            "brushed": {"type": "roughconductor", "material": "Al", "distribution": "ggx",
                        "alpha_u": 0.05, "alpha_v": 0.3}},
            "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "plain"}]})",
                                        "test.json");
    REQUIRE(s.materials.size() == 5);
    const wp::Material& plain = s.materials[0];
    // Material "none" without eta and k: the perfect mirror, the mirror kind.
    CHECK(plain.kind == wp::MaterialKind::Mirror);
    CHECK(plain.reflectance == glm::dvec3(1.0));
    const wp::Material& gold = s.materials[1];
    CHECK(gold.kind == wp::MaterialKind::Conductor);
    CHECK(gold.metal == "Au");
    CHECK(gold.eta.x == Approx(0.1431189557));
    CHECK(gold.k.z == Approx(1.6032152899));
    CHECK(gold.reflectance == glm::dvec3(1, 0.5, 1));
    const wp::Material& given = s.materials[2];
    CHECK(given.kind == wp::MaterialKind::Conductor);
    CHECK(given.eta == glm::dvec3(1, 2, 3));
    CHECK(given.k == glm::dvec3(4, 5, 6));
    const wp::Material& rough = s.materials[3];
    CHECK(rough.kind == wp::MaterialKind::RoughConductor);
    CHECK(rough.eta == glm::dvec3(0.0)); // "none": eta 0, k 1
    CHECK(rough.k == glm::dvec3(1.0));
    CHECK(rough.distribution == wp::MicrofacetDistribution::Beckmann);
    CHECK(rough.alpha_u == 0.1);
    CHECK(rough.alpha_v == 0.1);
    const wp::Material& brushed = s.materials[4];
    CHECK(brushed.distribution == wp::MicrofacetDistribution::Ggx);
    CHECK(brushed.alpha_u == 0.05);
    CHECK(brushed.alpha_v == 0.3);
    CHECK(brushed.metal == "Al");
}

TEST_CASE("loader: dielectrics read Mitsuba's parameters, defaults and named indices",
          "[scene][load]") {
    const wp::Scene s = wp::parse_scene(R"({"camera": )" + kSceneCamera + R"(, "materials": {
            "plain": {"type": "dielectric"},
            "water": {"type": "dielectric", "int_ior": "water", "ext_ior": 1.1,
                      "specular_transmittance": [0.5, 0.6, 0.7]},
            "pane": {"type": "thindielectric", "int_ior": "diamond", "ext_ior": "vacuum",
                     "specular_reflectance": [0.2, 0.3, 0.4]}},
            "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "plain"}]})",
                                        "test.json");
    REQUIRE(s.materials.size() == 3);
    const wp::Material& plain = s.materials[0];
    CHECK(plain.kind == wp::MaterialKind::Dielectric);
    CHECK(plain.int_ior == 1.5046); // Mitsuba's defaults: BK7 in air
    CHECK(plain.ext_ior == 1.000277);
    CHECK(plain.reflectance == glm::dvec3(1.0));
    CHECK(plain.transmittance == glm::dvec3(1.0));
    const wp::Material& water = s.materials[1];
    CHECK(water.int_ior == 1.3330);
    CHECK(water.ext_ior == 1.1);
    CHECK(water.transmittance == glm::dvec3(0.5, 0.6, 0.7));
    const wp::Material& pane = s.materials[2];
    CHECK(pane.kind == wp::MaterialKind::ThinDielectric);
    CHECK(pane.int_ior == 2.419);
    CHECK(pane.ext_ior == 1.0);
    CHECK(pane.reflectance == glm::dvec3(0.2, 0.3, 0.4));
}

TEST_CASE("loader: plastic reads Mitsuba's parameters and defaults", "[scene][load]") {
    const wp::Scene s = wp::parse_scene(R"({"camera": )" + kSceneCamera + R"(, "materials": {
            "plain": {"type": "plastic"},
            "varnish": {"type": "plastic", "diffuse_reflectance": [0.4, 0.2, 0.1],
                        "specular_reflectance": [0.9, 0.9, 0.8], "int_ior": "acrylic glass",
                        "nonlinear": true}},
            "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "plain"}]})",
                                        "test.json");
    REQUIRE(s.materials.size() == 2);
    const wp::Material& plain = s.materials[0];
    CHECK(plain.kind == wp::MaterialKind::Plastic);
    CHECK(plain.int_ior == 1.49); // polypropylene, Mitsuba's default
    CHECK(plain.ext_ior == 1.000277);
    CHECK(plain.reflectance == glm::dvec3(0.5));
    CHECK(plain.specular == glm::dvec3(1.0));
    CHECK_FALSE(plain.nonlinear);
    const wp::Material& varnish = s.materials[1];
    CHECK(varnish.reflectance == glm::dvec3(0.4, 0.2, 0.1));
    CHECK(varnish.specular == glm::dvec3(0.9, 0.9, 0.8));
    CHECK(varnish.int_ior == 1.49);
    CHECK(varnish.nonlinear);
}
