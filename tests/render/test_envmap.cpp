// The envmap emitter end to end (kernels/lights/envmap.h, shade.cl's
// escape): a diffuse floor lit by an environment map against the map's
// radiance integrated by quadrature on the host, with next-event estimation
// and BSDF sampling weighed by multiple importance sampling, and each
// strategy's share checked by the white furnace. Monte Carlo checks are
// held to five standard errors of the estimate.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "render/device_scene.hpp"
#include "render/environment_tables.hpp"
#include "support/float_image.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;
using wp::test::float_image;

namespace {

constexpr double kSigmas = 5.0;

Emitter envmap(std::shared_ptr<const TextureImage> image, const glm::dmat3& to_world,
               double scale) {
    Emitter e;
    e.kind = EmitterKind::Envmap;
    e.image = std::move(image);
    e.to_world = to_world;
    e.value = glm::dvec3(scale);
    return e;
}

// A 32 x 16 sky: a gradient from a bright zenith to a dim horizon, a dark
// ground, and a sun of one texel 2000 times the sky, 30 degrees up.
std::shared_ptr<const TextureImage> sky_with_sun() {
    const std::uint32_t w = 32, h = 16;
    std::vector<glm::dvec3> texels;
    for (std::uint32_t j = 0; j < h; ++j)
        for (std::uint32_t i = 0; i < w; ++i) {
            const double up = 1.0 - j / (h - 1.0) * 2.0; // +1 at the zenith, -1 at the nadir
            texels.push_back(up > 0.0 ? glm::dvec3(0.3, 0.5, 1.0) * (0.5 + up)
                                      : glm::dvec3(0.05, 0.04, 0.03));
        }
    texels[5 * w + 9] = glm::dvec3(2000.0, 1800.0, 1500.0);
    return float_image(w, h, texels);
}

} // namespace

TEST_CASE("envmap: a diffuse floor shows rho / pi times the sky's cosine-weighted integral",
          "[emitters][envmap][statistical]") {
    // The map's up (+y) turned to the world's +z, and turned about it: the
    // floor z = 0 sees the map's upper hemisphere.
    const glm::dmat3 to_world =
        glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0, 0, 1))) *
        glm::dmat3(glm::rotate(glm::dmat4(1.0), M_PI / 2.0, glm::dvec3(1, 0, 0)));
    const double scale = 0.8;
    const glm::dvec3 rho(0.8, 0.6, 0.4);
    Scene scene;
    auto floor = test::add_material(scene, MaterialKind::Diffuse, rho);
    test::add_quad(scene, {-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, {-20, 20, 0}, floor);
    scene.camera = test::make_camera({0, 0, 2}, {0, 0, 0}, {0, 1, 0}, 60.0, 8, 8);
    const auto image = sky_with_sun();
    scene.emitters.push_back(envmap(image, to_world, scale));

    // E = integral over the upper hemisphere of L cos theta, by the midpoint
    // rule in (phi, cos theta) (equal solid angles) on the host reference.
    const EnvironmentTables map = build_environment_tables(*image);
    const glm::dmat3 to_local = glm::transpose(to_world);
    const int n_phi = 4096, n_z = 2048;
    glm::dvec3 irradiance(0.0);
    for (int b = 0; b < n_z; ++b) {
        const double z = (b + 0.5) / n_z, r = std::sqrt(1.0 - z * z);
        for (int a = 0; a < n_phi; ++a) {
            const double phi = 2.0 * M_PI * (a + 0.5) / n_phi;
            const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
            irradiance += map.radiance(to_local * d) * z;
        }
    }
    irradiance *= scale * 2.0 * M_PI / (static_cast<double>(n_phi) * n_z);

    // With the power heuristic, and with the light sample alone (--mis
    // light: an escaping ray adds nothing the light sample could have found).
    for (MisStrategy mis : {MisStrategy::Power, MisStrategy::LightOnly}) {
        INFO("--mis " << to_string(mis));
        IntegratorOptions options;
        options.sampler = Sampler::Independent;
        options.mis = mis;
        test::Rendered r = test::render(scene, 1024, 1, 0, options);
        CHECK(r.stats.nonfinite_samples == 0);
        for (int c = 0; c < 3; ++c) {
            const double expected = rho[c] / M_PI * irradiance[c];
            test::MeanWithError m = test::image_mean(r.film, c);
            INFO("channel " << c << ": " << m.mean << " +- " << m.standard_error << ", expected "
                            << expected);
            CHECK(std::abs(m.mean - expected) < kSigmas * m.standard_error);
            CHECK(m.standard_error < 0.01 * expected); // the test has power
        }
    }
}

TEST_CASE("envmap: a white furnace in a uniform map shows its radiance",
          "[emitters][envmap][statistical]") {
    // As the constant emitter's furnace (test_emitters.cpp), lit by a 1 x 1
    // map: next-event estimation samples the map's patches, a BSDF sample
    // that escapes looks the map up, and the two weights must sum to one.
    const glm::dvec3 radiance(0.5, 1.0, 2.0);
    Scene scene;
    auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(1.0));
    scene.spheres.push_back({{-0.6, 0, 0}, 0.5, white});
    test::add_box_inward(scene, {0.0, -0.5, -0.5}, {1.0, 0.5, 0.5}, white);
    scene.emitters.push_back(envmap(float_image(1, 1, {radiance / 2.0}), glm::dmat3(1.0), 2.0));
    scene.camera = test::make_camera({0.2, -3, 0.8}, {0.2, 0, 0}, {0, 0, 1}, 40.0, 16, 16);
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    test::Rendered r = test::render(scene, 256, 1, 0, options);
    CHECK(r.stats.nonfinite_samples == 0);
    for (int c = 0; c < 3; ++c) {
        test::MeanWithError m = test::image_mean(r.film, c);
        INFO("channel " << c << ": " << m.mean << " +- " << m.standard_error << ", expected "
                        << radiance[c]);
        CHECK(std::abs(m.mean - radiance[c]) < kSigmas * m.standard_error);
        CHECK(m.standard_error < 0.005 * radiance[c]);
    }
}

TEST_CASE("envmap: a feature switch of its own, first among the emitters", "[emitters][envmap]") {
    Scene scene = test::hexroom(8, 8);
    CHECK_FALSE(analyse_features(scene).envmap_light);
    const std::size_t texels_before = flatten_scene(scene).texels.size();
    Emitter point;
    point.kind = EmitterKind::Point;
    point.position = {0, 0, 1};
    scene.emitters.push_back(point);
    scene.emitters.push_back(envmap(sky_with_sun(), glm::dmat3(1.0), 1.0));
    const SceneFeatures f = analyse_features(scene);
    CHECK(f.envmap_light);
    CHECK_FALSE(f.constant_light);
    CHECK(f.build_options().find("-D WP_HAS_ENVMAP_LIGHT=1") != std::string::npos);
    const DeviceScene flat = flatten_scene(scene);
    REQUIRE(flat.emitters.size() == 2);
    CHECK(flat.emitters[0].kind == WP_EMITTER_ENVMAP); // where an escaping ray looks
    CHECK(flat.emitters[0].width == 32);
    CHECK(flat.emitters[0].height == 16);
    // Its texels as floats after the textures', its tables: 15 rows of 32,
    // and the rows' two cosines.
    CHECK(flat.texels.size() == texels_before + 3 * 32 * 16);
    CHECK(flat.environment_cdf.size() == 15 + 15 * 32 + 2 * 15);
    CHECK(flat.environment_cdf[14] == 1.0f);
    // Row j's cos(theta_j) and cos(theta_j) - cos(theta_{j+1}), theta_j =
    // pi j / 15, against the plain cosines in double (exact enough here).
    const float* geometry = flat.environment_cdf.data() + 15 + 15 * 32;
    for (int j = 0; j < 15; ++j) {
        const double cos_j = std::cos(M_PI * j / 15.0), cos_next = std::cos(M_PI * (j + 1) / 15.0);
        INFO("row " << j);
        CHECK(std::abs(geometry[2 * j] - cos_j) <= 6e-8);
        CHECK(std::abs(geometry[2 * j + 1] - (cos_j - cos_next)) <= 1e-7 * (cos_j - cos_next));
    }
    // A black map emits nothing: left out, as a black point light is.
    scene.emitters.back() =
        envmap(float_image(2, 2, std::vector<glm::dvec3>(4, glm::dvec3(0.0))), glm::dmat3(1.0), 1);
    CHECK(flatten_scene(scene).emitters.size() == 1);
}
