// The materials at their extremes (docs/stability.md, "Materials"): an index
// of refraction of 1 must be no interface at all, and indices of 1e4, paths
// trapped by total internal reflection inside a sphere, roughness from 1e-4 to
// the limit of 4 and grazing views must all render finite, non-negative
// images.
#include "stability.hpp"

#include <cmath>

#include "render/integrator_options.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

Scene agreement_scene(const std::string& name, int width, int height) {
    Scene scene =
        load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/mitsuba/" + name + ".json");
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

Material& named(Scene& scene, const std::string& name) {
    for (Material& m : scene.materials)
        if (m.name == name)
            return m;
    FAIL("no material " << name);
    throw;
}

// Every pixel finite and non-negative, no sample dropped as non-finite.
void check_finite(const test::Rendered& r, const std::string& what) {
    INFO(what);
    CHECK(r.stats.nonfinite_samples == 0);
    const Image mean = r.film.mean();
    std::size_t bad = 0;
    for (float v : mean.rgb)
        bad += std::isfinite(v) && v >= 0.0f ? 0 : 1;
    CHECK(bad == 0);
}

} // namespace

TEST_CASE("materials: a dielectric of index 1 is no interface", "[stability][materials]") {
    // The glass scene with its two dielectric spheres and its thin pane
    // index-matched (int_ior = ext_ior, eta exactly 1) against the same scene
    // without them. Next-event estimation off: a shadow ray stops at any
    // surface, also an invisible one, but a BSDF-sampled path must pass it as
    // if it were not there.
    Scene matched = agreement_scene("glass", 24, 16);
    for (const char* name : {"glass", "water", "pane"}) {
        Material& m = named(matched, name);
        m.int_ior = m.ext_ior;
        m.transmittance = glm::dvec3(1.0);
    }
    Scene without = matched;
    const std::uint32_t pane =
        static_cast<std::uint32_t>(&named(matched, "pane") - matched.materials.data());
    without.triangles.clear();
    for (const Triangle& t : matched.triangles)
        if (t.material != pane)
            without.triangles.push_back(t);
    REQUIRE(without.triangles.size() + 2 == matched.triangles.size());
    std::erase_if(without.spheres, [&](const Sphere& s) {
        return matched.materials[s.material].kind == MaterialKind::Dielectric;
    });
    REQUIRE(without.spheres.size() == 1);

    IntegratorOptions bsdf_only;
    bsdf_only.next_event_estimation = false;
    const test::Rendered a = test::render(matched, 1024, 21, 0, bsdf_only);
    const test::Rendered b = test::render(without, 1024, 22, 0, bsdf_only);
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c);
        CHECK(image_mean_sigmas(a.film, b.film, c) < kSigmas);
    }
    const BlockComparison blocks = compare_blocks(a.film, b.film, 4);
    INFO(blocks.outside << " of " << blocks.blocks << " block means over 5 sigma; the farthest "
                        << blocks.worst_where);
    CHECK(blocks.outside == 0);
}

TEST_CASE("materials: extreme indices, trapped paths and roughness render finite",
          "[stability][materials]") {
    {
        // Indices of 1e4 (nearly every ray reflects) and of 1.0001, on the
        // glass and on the plastic.
        for (double ior : {1e4, 1.0001}) {
            Scene glass = agreement_scene("glass", 16, 12);
            for (const char* name : {"glass", "water", "pane"})
                named(glass, name).int_ior = ior;
            check_finite(test::render(glass, 16, 3), "glass, int_ior " + std::to_string(ior));
            Scene plastic = agreement_scene("plastic", 16, 12);
            for (const char* name : {"floor", "default", "red", "blue"})
                named(plastic, name).int_ior = ior;
            check_finite(test::render(plastic, 16, 3), "plastic, int_ior " + std::to_string(ior));
        }
    }
    {
        // The eye inside the diamond-like sphere: every path starts inside
        // and meets its surface from within, beyond the critical angle for
        // most directions (total internal reflection).
        Scene inside = agreement_scene("glass", 16, 12);
        named(inside, "glass").int_ior = 2.419;
        inside.camera.eye = inside.spheres[0].center;
        inside.camera.look_at = inside.spheres[0].center + glm::dvec3(1.0, 0.2, 0.3);
        const test::Rendered r = test::render(inside, 32, 5);
        check_finite(r, "the eye inside a sphere of index 2.419");
        double sum = 0.0;
        for (float v : r.film.mean().rgb)
            sum += v;
        CHECK(sum > 0.0); // light gets out (and in)
    }
    {
        // Roughness at the floor of 1e-4 and at the limit of 4, both
        // distributions, from above and level with the spheres (grazing
        // their silhouettes and the floor).
        for (double alpha : {1e-4, 4.0}) {
            Scene metals = agreement_scene("metals", 16, 12);
            named(metals, "gold").alpha_u = named(metals, "gold").alpha_v = alpha;
            named(metals, "aluminium").alpha_u = named(metals, "aluminium").alpha_v = alpha;
            check_finite(test::render(metals, 16, 7), "roughness " + std::to_string(alpha));
            metals.camera.eye = glm::dvec3(0.0, 0.9, 6.5); // level with the centres
            metals.camera.look_at = glm::dvec3(0.0, 0.9, 0.0);
            check_finite(test::render(metals, 16, 7),
                         "roughness " + std::to_string(alpha) + ", level with the spheres");
        }
    }
    {
        // The rough plastic at the same extremes: its coating's indices of
        // 1e4 (the base's 1 / (1 - R_int) near a division by 0), 1.0001 and
        // 0.5 (a coating less dense than outside), its roughness at 1e-4 and
        // 4, from above and level with the spheres.
        const char* const names[] = {"floor", "default", "red", "blue"};
        for (double ior : {1e4, 1.0001, 0.5}) {
            Scene plastic = agreement_scene("roughplastic", 16, 12);
            for (const char* name : names)
                named(plastic, name).int_ior = ior;
            check_finite(test::render(plastic, 16, 3),
                         "roughplastic, int_ior " + std::to_string(ior));
        }
        for (double alpha : {1e-4, 4.0}) {
            Scene plastic = agreement_scene("roughplastic", 16, 12);
            for (const char* name : names)
                named(plastic, name).alpha_u = named(plastic, name).alpha_v = alpha;
            check_finite(test::render(plastic, 16, 7),
                         "roughplastic, roughness " + std::to_string(alpha));
            plastic.camera.eye = glm::dvec3(0.0, 0.9, 6.5);
            plastic.camera.look_at = glm::dvec3(0.0, 0.9, 0.0);
            check_finite(test::render(plastic, 16, 7), "roughplastic, roughness " +
                                                           std::to_string(alpha) +
                                                           ", level with the spheres");
        }
    }
}
