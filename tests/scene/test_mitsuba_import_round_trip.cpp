// JSON -> Mitsuba 3 XML -> wavepath: every scene of the agreement suite and
// the two reference scenes, exported by wp::export_mitsuba (the independent
// writer, docs/mitsuba-export.md) and read back by the Mitsuba reader
// (scene/mitsuba/load_mitsuba.hpp), must be the scene the JSON loader made:
// the same camera to double rounding, the same materials, the same
// triangles to float32 rounding (the export's PLY precision) in the export's
// order (grouped by material), the same spheres and emission.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/mitsuba_export.hpp"
#include "support/temp_dir.hpp"

namespace {

const std::string kSource = WAVEPATH_SOURCE_DIR;

// Compared as floats, never converted back (see test_mitsuba_export.cpp:
// GCC at -O3 may drop a double -> float -> double round trip).
std::array<float, 3> as_float(const glm::dvec3& v) {
    return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

void check_relative(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    INFO("(" << a.x << ", " << a.y << ", " << a.z << ") against (" << b.x << ", " << b.y << ", "
             << b.z << ")");
    CHECK(glm::length(a - b) <= tolerance * std::max({glm::length(b), 1.0}));
}

// The camera's frame as the renderer builds it (device_scene.cpp).
struct Frame {
    glm::dvec3 forward, right, up;
};
Frame frame_of(const wp::Camera& c) {
    const glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    return {forward, right, glm::cross(right, forward)};
}

void check_round_trip(const std::string& json) {
    INFO(json);
    const wp::Scene original = wp::load_scene(kSource + "/" + json);
    wp::test::TempDir dir;
    const wp::MitsubaExport exported = wp::export_mitsuba(original, "scene");
    wp::write_mitsuba(exported, dir / "scene.xml");
    const wp::Scene read = wp::load_scene(dir / "scene.xml");

    // Every reflecting BSDF the export writes is twosided: nothing to warn.
    CHECK(read.warnings.empty());

    const wp::Camera &a = read.camera, &b = original.camera;
    CHECK(a.width == b.width);
    CHECK(a.height == b.height);
    CHECK(a.vertical_fov_degrees == Approx(b.vertical_fov_degrees).epsilon(1e-9));
    check_relative(a.eye, b.eye, 1e-9);
    const Frame fa = frame_of(a), fb = frame_of(b);
    check_relative(fa.forward, fb.forward, 1e-9);
    check_relative(fa.right, fb.right, 1e-9);
    check_relative(fa.up, fb.up, 1e-9);
    CHECK(a.aperture_radius == b.aperture_radius);
    if (b.aperture_radius > 0.0)
        CHECK(a.focus_distance == b.focus_distance);
    CHECK(a.filter == b.filter);
    CHECK(a.filter_radius == b.filter_radius);
    CHECK(a.filter_stddev == b.filter_stddev);

    // The triangles in the export's order: by material, then as they were.
    std::map<std::uint32_t, std::vector<wp::Triangle>> groups;
    for (const wp::Triangle& t : original.triangles)
        groups[t.material].push_back(t);
    std::vector<wp::Triangle> expected;
    for (const auto& [material, triangles] : groups)
        expected.insert(expected.end(), triangles.begin(), triangles.end());
    REQUIRE(read.triangles.size() == expected.size());
    std::map<std::uint32_t, std::uint32_t> material_of; // original -> read
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const wp::Triangle &r = read.triangles[i], &o = expected[i];
        for (std::size_t k = 0; k < 3; ++k)
            CHECK(as_float(r.v[k]) == as_float(o.v[k]));
        CHECK(r.has_normals == o.has_normals);
        material_of.emplace(o.material, r.material);
        CHECK(material_of.at(o.material) == r.material); // one material stays one
    }
    REQUIRE(read.spheres.size() == original.spheres.size());
    for (std::size_t i = 0; i < read.spheres.size(); ++i) {
        CHECK(read.spheres[i].center == original.spheres[i].center);
        CHECK(read.spheres[i].radius == original.spheres[i].radius);
        material_of.emplace(original.spheres[i].material, read.spheres[i].material);
        CHECK(material_of.at(original.spheres[i].material) == read.spheres[i].material);
    }
    // Each material the shapes use, with every value that renders; no more.
    CHECK(read.materials.size() == material_of.size());
    for (const auto& [o, r] : material_of) {
        const wp::Material &mo = original.materials[o], &mr = read.materials[r];
        INFO("material '" << mo.name << "' read back as '" << mr.name << "'");
        CHECK(mr.kind == mo.kind);
        // Textures are numbered in another order (the XML reader's is the
        // shapes' first use): the same texture under each parameter, then
        // every other value.
        wp::Material cr = mr, co = mo;
        for (auto field : {&wp::Material::reflectance_texture, &wp::Material::specular_texture,
                           &wp::Material::transmittance_texture, &wp::Material::alpha_u_texture,
                           &wp::Material::alpha_v_texture}) {
            REQUIRE((mo.*field == 0) == (mr.*field == 0));
            if (mo.*field != 0) {
                const wp::Texture &to = original.textures[mo.*field - 1],
                                  &tr = read.textures[mr.*field - 1];
                CHECK(tr.kind == to.kind);
                CHECK(tr.to_u == to.to_u);
                CHECK(tr.to_v == to.to_v);
                CHECK(tr.color0 == to.color0);
                CHECK(tr.color1 == to.color1);
                CHECK(tr.filter == to.filter);
                CHECK(tr.wrap == to.wrap);
                CHECK(tr.raw == to.raw);
                CHECK((tr.image == nullptr) == (to.image == nullptr));
                if (tr.image && to.image)
                    CHECK(tr.image->texels == to.image->texels);
            }
            cr.*field = co.*field = 0;
        }
        CHECK(cr.rendered_fields() == co.rendered_fields());
    }
    // The emitters: positions, values and angles exactly (shortest decimal
    // text), a spot's axis through its lookat to double rounding.
    REQUIRE(read.emitters.size() == original.emitters.size());
    for (std::size_t i = 0; i < read.emitters.size(); ++i) {
        const wp::Emitter &r = read.emitters[i], &o = original.emitters[i];
        CHECK(r.kind == o.kind);
        CHECK(r.value == o.value);
        CHECK(r.position == o.position);
        check_relative(r.direction, o.direction, 1e-12);
        CHECK(r.cutoff_angle == o.cutoff_angle);
        CHECK(r.beam_width == o.beam_width);
        // An envmap's rotation exactly (its matrix as shortest decimal text),
        // its image by content.
        CHECK(r.to_world == o.to_world);
        CHECK((r.image == nullptr) == (o.image == nullptr));
        if (r.image && o.image)
            CHECK(r.image->texels == o.image->texels);
    }
}

} // namespace

TEST_CASE("mitsuba import: the agreement scenes survive JSON -> XML -> scene",
          "[scene][mitsuba][import]") {
    for (const char* name : {"metals", "glass", "plastic", "roughplastic", "textures", "point",
                             "spot", "sun", "sky", "envmap"})
        check_round_trip(std::string("tests/data/mitsuba/") + name + ".json");
}

TEST_CASE("mitsuba import: the hexroom and the Cornell box survive JSON -> XML -> scene",
          "[scene][mitsuba][import]") {
    check_round_trip("scenes/hexroom.json");
    check_round_trip("scenes/cornell-box.json");
}
