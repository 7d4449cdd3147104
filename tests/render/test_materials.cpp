// The materials end to end: next-event estimation weighed by multiple
// importance sampling must estimate what BSDF sampling alone does, for
// glossy vertices (the rough conductor) and around delta surfaces that are not
// the mirror kind (a smooth conductor, which the mirror next-event estimation
// must leave alone).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "render/integrator_options.hpp"
#include "scene/load.hpp"
#include "scene/material.hpp"
#include "support/render_helpers.hpp"

using namespace wp;
using namespace wp::test;

namespace {

Scene rough_metals(int width, int height) {
    Scene scene =
        load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/materials/rough-metals.json");
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

Material& material_named(Scene& scene, const std::string& name) {
    for (Material& m : scene.materials)
        if (m.name == name)
            return m;
    FAIL("no material " << name);
    throw;
}

// Image means and 4x4-pixel block means of the two estimators, per channel,
// within 5 combined standard errors; BSDF sampling alone, the noisier, at
// `reference_spp` (default: spp).
void check_same_estimate(const Scene& scene, std::uint32_t spp, std::uint32_t reference_spp = 0) {
    IntegratorOptions nee, bsdf_only;
    bsdf_only.next_event_estimation = false;
    const Rendered a = render(scene, spp, 3, 0, nee);
    const Rendered b = render(scene, reference_spp > 0 ? reference_spp : spp, 4, 0, bsdf_only);
    CHECK(a.stats.nonfinite_samples == 0);
    CHECK(b.stats.nonfinite_samples == 0);
    for (int c = 0; c < 3; ++c) {
        const MeanWithError ma = image_mean(a.film, c), mb = image_mean(b.film, c);
        INFO("channel " << c << ": with NEE " << ma.mean << " +- " << ma.standard_error
                        << ", BSDF sampling alone " << mb.mean << " +- " << mb.standard_error);
        CHECK(sigmas_apart(ma, mb) < 5.0);
    }
    const Image mean_a = a.film.mean(), mean_b = b.film.mean();
    const Image var_a = a.film.variance_of_mean(), var_b = b.film.variance_of_mean();
    constexpr int kBlock = 4;
    int blocks = 0, far = 0;
    for (int by = 0; by + kBlock <= scene.camera.height; by += kBlock)
        for (int bx = 0; bx + kBlock <= scene.camera.width; bx += kBlock)
            for (int c = 0; c < 3; ++c) {
                MeanWithError ea, eb;
                double va = 0.0, vb = 0.0;
                for (int y = by; y < by + kBlock; ++y)
                    for (int x = bx; x < bx + kBlock; ++x) {
                        ea.mean += mean_a.pixel(x, y)[c];
                        eb.mean += mean_b.pixel(x, y)[c];
                        va += var_a.pixel(x, y)[c];
                        vb += var_b.pixel(x, y)[c];
                    }
                ea.standard_error = std::sqrt(va);
                eb.standard_error = std::sqrt(vb);
                ++blocks;
                far += sigmas_apart(ea, eb) > 5.0 ? 1 : 0;
            }
    INFO(far << " of " << blocks << " block means more than 5 sigma apart");
    CHECK(far == 0);
}

} // namespace

TEST_CASE("materials: rough conductors' MIS estimate equals BSDF sampling alone",
          "[render][materials][statistical]") {
    check_same_estimate(rough_metals(24, 16), 512);
}

TEST_CASE("materials: a smooth conductor wall is no planar mirror for --mirror-nee",
          "[render][materials][statistical]") {
    // The back wall a polished aluminium conductor (flat, delta, not the mirror
    // kind) and the floor lit through it; a mirror sphere so that the mirror
    // next-event estimation is compiled in. A path diffuse -> wall -> light
    // must keep weight 1: only mirrors are sampled by the mirrored strategy.
    Scene scene = rough_metals(24, 16);
    Material& wall = material_named(scene, "wall");
    wall.kind = MaterialKind::Conductor;
    wall.eta = find_metal("Al")->eta;
    wall.k = find_metal("Al")->k;
    wall.reflectance = glm::dvec3(1.0);
    Material& gold = material_named(scene, "gold");
    gold.kind = MaterialKind::Mirror;
    gold.reflectance = glm::dvec3(0.9);
    check_same_estimate(scene, 512);
}

TEST_CASE("materials: rough dielectrics' two-sided light sampling with MIS equals BSDF sampling "
          "alone",
          "[render][materials][statistical]") {
    // Next-event estimation at a rough dielectric sees lights on both sides
    // (a shadow ray from the other side for a light behind it) and weighs
    // them by the power heuristic against the BSDF's samples, reflected or
    // transmitted; BSDF sampling alone (next-event estimation off) is the
    // reference.
    Scene scene =
        load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/mitsuba/roughglass.json");
    scene.camera.width = 24;
    scene.camera.height = 16;
    // Broad lobes, so that light samples carry much of the estimate.
    for (Material& m : scene.materials)
        if (m.kind == MaterialKind::RoughDielectric)
            m.alpha_u = m.alpha_v = 0.8;
    check_same_estimate(scene, 1024, 8192);
}

TEST_CASE("materials: rough plastics' MIS estimate equals BSDF sampling alone",
          "[render][materials][statistical]") {
    // Next-event estimation lights both of a rough plastic's lobes, the
    // coating and the base, weighed against the BSDF's mixture density by
    // the power heuristic; BSDF sampling alone is the reference.
    Scene scene =
        load_scene(std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/mitsuba/roughplastic.json");
    scene.camera.width = 24;
    scene.camera.height = 16;
    check_same_estimate(scene, 512, 2048);
}
