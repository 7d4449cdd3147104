// The point, spot, directional and constant emitters (kernels/lights.h,
// docs/lights-and-camera.md) against closed forms: the irradiance a point
// light and a sun give a diffuse plane, the spot's falloff against a
// double-precision evaluation of Mitsuba 3.9.1's formula, and a white
// furnace in a constant environment. Monte Carlo checks are held to five
// standard errors of the estimate, from the film's own sample variance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/device_scene.hpp"
#include "support/kernel_test_util.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

constexpr double kSigmas = 5.0;

Emitter make_emitter(EmitterKind kind, glm::dvec3 value) {
    Emitter e;
    e.kind = kind;
    e.value = value;
    return e;
}

// A diffuse floor z = 0 of reflectance rho, 40 x 40, and a camera at height
// `eye_height` looking straight down at the origin. The plane is parallel to
// the film, so the box filter's uniform film positions are uniform points of
// the floor rectangle [-half_x, half_x] x [-half_y, half_y] the image sees.
struct FloorView {
    Scene scene;
    double half_x = 0.0, half_y = 0.0;
};

FloorView floor_view(glm::dvec3 rho, double eye_height, double fov, int width, int height) {
    FloorView v;
    auto floor = test::add_material(v.scene, MaterialKind::Diffuse, rho);
    test::add_quad(v.scene, {-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, {-20, 20, 0}, floor);
    v.scene.camera =
        test::make_camera({0, 0, eye_height}, {0, 0, 0}, {0, 1, 0}, fov, width, height);
    v.half_y = eye_height * std::tan(0.5 * fov * M_PI / 180.0);
    v.half_x = v.half_y * width / height;
    return v;
}

// The mean of f(x, y) over the rectangle, by the midpoint rule on an n x n
// grid in double precision (f is smooth there: the error is far below the
// tolerances it is compared with).
template <typename F> double rectangle_mean(double half_x, double half_y, F f, int n = 1000) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            sum +=
                f(-half_x + (i + 0.5) * 2.0 * half_x / n, -half_y + (j + 0.5) * 2.0 * half_y / n);
    return sum / (static_cast<double>(n) * n);
}

} // namespace

TEST_CASE("emitters: a point light gives a diffuse plane rho / pi * I cos / r^2",
          "[emitters][statistical]") {
    const glm::dvec3 rho(0.8, 0.6, 0.4), intensity(10.0, 20.0, 5.0);
    const glm::dvec3 light(0.3, -0.2, 1.5);
    FloorView v = floor_view(rho, 2.0, 60.0, 16, 12);
    Emitter e = make_emitter(EmitterKind::Point, intensity);
    e.position = light;
    v.scene.emitters.push_back(e);
    // cos / r^2 = h / r^3 at a floor point, h the light's height.
    const double geometry = rectangle_mean(v.half_x, v.half_y, [&](double x, double y) {
        const double dx = x - light.x, dy = y - light.y;
        const double r = std::sqrt(dx * dx + dy * dy + light.z * light.z);
        return light.z / (r * r * r);
    });
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    test::Rendered r = test::render(v.scene, 256, 1, 0, options);
    CHECK(r.stats.nonfinite_samples == 0);
    for (int c = 0; c < 3; ++c) {
        test::MeanWithError m = test::image_mean(r.film, c);
        const double expected = rho[c] / M_PI * intensity[c] * geometry;
        // The estimate varies only with the point of the pixel a sample
        // sees; a float32 rounding floor of 1e-5 is added to the tolerance.
        INFO("channel " << c << ": " << m.mean << " +- " << m.standard_error << ", expected "
                        << expected << ", relative error " << (m.mean - expected) / expected);
        CHECK(std::abs(m.mean - expected) < kSigmas * m.standard_error + 1e-5 * expected);
        CHECK(m.standard_error > 0.0);
    }
}

TEST_CASE("emitters: a directional light gives a diffuse plane rho / pi * E cos theta",
          "[emitters]") {
    const glm::dvec3 rho(0.8, 0.6, 0.4), irradiance(3.0, 2.0, 1.0);
    FloorView v = floor_view(rho, 2.0, 60.0, 16, 12);
    Emitter e = make_emitter(EmitterKind::Directional, irradiance);
    e.direction = glm::normalize(glm::dvec3(0.4, -0.3, -1.0)); // the way the light travels
    v.scene.emitters.push_back(e);
    const double cos_theta = -e.direction.z;
    test::Rendered r = test::render(v.scene, 16);
    CHECK(r.stats.nonfinite_samples == 0);
    // Every sample carries the same value: only float32 rounding is left.
    const Image mean = r.film.mean();
    double worst = 0.0;
    for (std::size_t i = 0; i < mean.rgb.size(); ++i) {
        const double expected =
            rho[static_cast<int>(i % 3)] / M_PI * irradiance[static_cast<int>(i % 3)] * cos_theta;
        worst = std::max(worst, std::abs(mean.rgb[i] - expected) / expected);
    }
    INFO("largest relative error of a pixel: " << worst);
    CHECK(worst < 1e-5);
}

TEST_CASE("emitters: a box's floor is in a sun's shadow where the box hides the sun",
          "[emitters]") {
    // A sun straight down onto a floor with a roof over part of the view:
    // the roofed pixels are black but for nothing (no other light), the rest
    // lit. The roof is a quad at z = 1 over x < 0.
    FloorView v = floor_view(glm::dvec3(0.5), 3.0, 40.0, 16, 16);
    auto roof = test::add_material(v.scene, MaterialKind::Diffuse, glm::dvec3(0.0));
    test::add_quad(v.scene, {-20, -20, 1}, {0, -20, 1}, {0, 20, 1}, {-20, 20, 1}, roof);
    Emitter e = make_emitter(EmitterKind::Directional, glm::dvec3(2.0));
    e.direction = {0, 0, -1};
    v.scene.emitters.push_back(e);
    v.scene.camera.eye = {0, 0, 0.5}; // under the roof, looking down
    const Image mean = test::render(v.scene, 4).film.mean();
    int dark = 0, lit = 0;
    for (std::size_t i = 0; i < mean.rgb.size(); i += 3) {
        dark += mean.rgb[i] == 0.0f;
        lit += std::abs(mean.rgb[i] - 0.5 / M_PI * 2.0) < 1e-5;
    }
    CHECK(dark + lit == 256);
    CHECK(dark > 64);
    CHECK(lit > 64);
}

TEST_CASE("emitters: the spot's falloff is Mitsuba 3.9.1's, linear in the angle", "[emitters]") {
    // wp_spot_falloff on the device against the formula in double: 1 inside
    // beam_width, (cutoff - theta) / (cutoff - beam_width) to the cutoff, 0
    // beyond (measured from Mitsuba 3.9.1's spot with mi.load_dict:
    // cutoff 30, beam 20 gives 0.9 at 21 degrees, 0.75 at 22.5, 0.5 at 25).
    const char* source = R"CL(
#include "lights.h"
__kernel void falloff(__global const WpEmitter* emitter, __global const float* cosines,
                      __global float* out, uint count) {
    uint i = get_global_id(0);
    if (i < count)
        out[i] = wp_spot_falloff(emitter, cosines[i]);
}
)CL";
    struct Case {
        double cutoff, beam;
    };
    for (const Case& c : {Case{30.0, 20.0}, Case{20.0, 15.0}, Case{90.0, 0.0}, Case{150.0, 100.0},
                          Case{10.0, 30.0}, Case{1.0, 0.5}}) {
        Scene scene;
        auto m = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
        test::add_quad(scene, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, m);
        scene.camera = test::make_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 40.0, 4, 4);
        Emitter e = make_emitter(EmitterKind::Spot, glm::dvec3(1.0));
        e.position = {0, 0, 2};
        e.direction = {0, 0, -1};
        e.cutoff_angle = c.cutoff;
        e.beam_width = c.beam;
        scene.emitters.push_back(e);
        const DeviceScene flat = flatten_scene(scene);
        REQUIRE(flat.emitters.size() == 1);
        std::vector<float> cosines;
        std::vector<double> expected;
        const int n = 4000;
        for (int i = 0; i <= n; ++i) {
            const double theta = std::min(180.0, c.cutoff * 1.2) * i / n * M_PI / 180.0;
            const float cos_theta = static_cast<float>(std::cos(theta));
            cosines.push_back(cos_theta);
            // The reference from the float cosine the kernel sees, in double.
            const double t = std::acos(std::min(1.0, static_cast<double>(cos_theta)));
            const double cutoff = c.cutoff * M_PI / 180.0, beam = c.beam * M_PI / 180.0;
            expected.push_back(t >= cutoff || static_cast<float>(std::cos(t)) <=
                                                  static_cast<float>(std::cos(cutoff))
                                   ? 0.0
                               : t <= beam ? 1.0
                                           : (cutoff - t) / (cutoff - beam));
        }
        cl::Kernel kernel(test::program(source, "spot_falloff_test.cl"), "falloff");
        // The buffers live until the kernel has run (a released one is freed).
        cl::Buffer emitter = test::upload(flat.emitters);
        cl::Buffer in = test::upload(cosines);
        cl::Buffer out = test::upload(std::vector<float>(cosines.size(), -1.0f));
        test::set_args(kernel, emitter, in, out, static_cast<cl_uint>(cosines.size()));
        test::launch(kernel, cosines.size());
        const std::vector<float> got = test::download<float>(out, cosines.size());
        double worst = 0.0;
        int mismatched_edges = 0;
        for (std::size_t i = 0; i < got.size(); ++i) {
            const double error = std::abs(got[i] - expected[i]);
            // Within a float ulp of the cutoff or beam edge the two sides
            // may round apart; count those, and hold the rest to 2e-4 (acos
            // in float near cos = 1 has an absolute error of ~3e-4 degrees
            // in the angle, over a transition of at least 0.5 degrees).
            if (error > 2e-4 && (std::abs(got[i]) < 1e-3 || std::abs(got[i] - 1.0) < 1e-3))
                ++mismatched_edges;
            else
                worst = std::max(worst, error);
        }
        INFO("cutoff " << c.cutoff << ", beam " << c.beam << ": worst error " << worst
                       << ", edge mismatches " << mismatched_edges);
        CHECK(worst < 2e-4);
        CHECK(mismatched_edges <= 2);
    }
}

TEST_CASE("emitters: a white furnace in a constant environment shows its radiance",
          "[emitters][statistical]") {
    // Albedo-1 diffuse objects (a sphere, and a box beside it that the
    // sphere's light bounces between) in a uniform environment L: every
    // surface has radiance L exactly, and so has the background. Next-event
    // estimation samples the environment's directions and weighs them
    // against BSDF sampling; a weight that failed to sum to one would move
    // the mean.
    const glm::dvec3 radiance(0.5, 1.0, 2.0);
    Scene scene;
    auto white = test::add_material(scene, MaterialKind::Diffuse, glm::dvec3(1.0));
    scene.spheres.push_back({{-0.6, 0, 0}, 0.5, white});
    test::add_box_inward(scene, {0.0, -0.5, -0.5}, {1.0, 0.5, 0.5}, white);
    scene.emitters.push_back(make_emitter(EmitterKind::Constant, radiance));
    scene.camera = test::make_camera({0.2, -3, 0.8}, {0.2, 0, 0}, {0, 0, 1}, 40.0, 16, 16);
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    test::Rendered r = test::render(scene, 256, 1, 0, options);
    CHECK(r.stats.nonfinite_samples == 0);
    const Image mean = r.film.mean(), variance = r.film.variance_of_mean();
    int outside = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < mean.rgb.size(); ++i) {
        const double expected = radiance[static_cast<int>(i % 3)];
        const double sigma = std::sqrt(static_cast<double>(variance.rgb[i]));
        const double z = std::abs(mean.rgb[i] - expected) / std::max(sigma, 1e-6 * expected);
        worst = std::max(worst, z);
        outside += z > kSigmas;
    }
    for (int c = 0; c < 3; ++c) {
        test::MeanWithError m = test::image_mean(r.film, c);
        INFO("channel " << c << ": " << m.mean << " +- " << m.standard_error << ", expected "
                        << radiance[c]);
        CHECK(std::abs(m.mean - radiance[c]) < kSigmas * m.standard_error);
        CHECK(m.standard_error < 0.005 * radiance[c]); // the test has power
    }
    INFO("largest pixel deviation " << worst << " sigma");
    CHECK(outside == 0);
}

TEST_CASE("emitters: each kind is a feature switch, off for the hexroom", "[emitters]") {
    Scene hexroom = test::hexroom(8, 8);
    const SceneFeatures plain = analyse_features(hexroom);
    CHECK_FALSE(plain.point_light);
    CHECK_FALSE(plain.spot_light);
    CHECK_FALSE(plain.directional_light);
    CHECK_FALSE(plain.constant_light);
    CHECK(plain.build_options().find("-D WP_HAS_POINT_LIGHT=0") != std::string::npos);
    CHECK(flatten_scene(hexroom).emitter_pick == 0.0f);

    Scene lit = hexroom;
    lit.emitters.push_back(make_emitter(EmitterKind::Spot, glm::dvec3(1.0)));
    const SceneFeatures f = analyse_features(lit);
    CHECK(f.spot_light);
    CHECK_FALSE(f.point_light);
    CHECK(f.planar_mirrors); // mirror next-event estimation holds beside other emitters
    const DeviceScene flat = flatten_scene(lit);
    CHECK_FALSE(flat.mirror_groups.empty()); // its tables are made
    REQUIRE(flat.emitters.size() == 1);
    // Chosen by power: the probabilities sum to 1.
    CHECK(flat.emitter_pick > 0.0f);
    CHECK(flat.emitter_pick < 1.0f); // the hexroom's triangles keep a share
    CHECK(flat.emitters[0].pick == Approx(flat.emitter_pick).epsilon(1e-6));
    CHECK(flat.emitters[0].cdf == 1.0f);
}

TEST_CASE("emitters: area lights and a point light together add up", "[emitters][statistical]") {
    // The same floor lit by a point light alone, by a square light alone, and
    // by both: the sum of the first two within noise (the choice between
    // them by power must divide by the right probabilities).
    const glm::dvec3 rho(0.7);
    FloorView v = floor_view(rho, 2.0, 40.0, 8, 8);
    auto light = test::add_material(v.scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(4));
    Scene area_only = v.scene;
    test::add_quad(area_only, {-3, -0.5, 3}, {-3, 0.5, 3}, {-2, 0.5, 3}, {-2, -0.5, 3}, light);
    Scene point_only = v.scene;
    Emitter e = make_emitter(EmitterKind::Point, glm::dvec3(3.0));
    e.position = {1, 1, 1.5};
    point_only.emitters.push_back(e);
    Scene both = area_only;
    both.emitters.push_back(e);
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    const test::MeanWithError a =
        test::image_mean(test::render(area_only, 512, 1, 0, options).film, 0);
    const test::MeanWithError p =
        test::image_mean(test::render(point_only, 512, 2, 0, options).film, 0);
    const test::MeanWithError s = test::image_mean(test::render(both, 512, 3, 0, options).film, 0);
    const test::MeanWithError sum{a.mean + p.mean, std::hypot(a.standard_error, p.standard_error)};
    INFO("area " << a.mean << " +- " << a.standard_error << ", point " << p.mean << " +- "
                 << p.standard_error << ", both " << s.mean << " +- " << s.standard_error);
    CHECK(test::sigmas_apart(s, sum) < kSigmas);
    CHECK(s.standard_error < 0.01 * s.mean);
}

TEST_CASE("emitters: a sphere light gives a diffuse plane rho / pi * pi L r^2 cos / d^2",
          "[emitters][sphere-light][statistical]") {
    // A sphere of radiance L wholly above the floor (height h > r) is seen
    // whole from every floor point, and gives it E = pi L (r / d)^2 cos
    // beta exactly, d the distance to the centre (a uniformly bright sphere
    // acts as a point of intensity pi r^2 L). A large near sphere beside the
    // view (its cone up to 90 degrees wide) and a small far one above it (a
    // 1e-3 radian cone).
    const glm::dvec3 rho(0.8, 0.6, 0.4), radiance(4.0, 3.0, 2.0);
    struct Case {
        const char* what;
        glm::dvec3 center;
        double radius;
        std::uint32_t spp;
    };
    for (const Case& c : {Case{"near", {2.3, 0.0, 0.85}, 0.8, 256},
                          Case{"small and far", {0.5, 0.4, 30.0}, 0.03, 64}}) {
        INFO(c.what);
        FloorView v = floor_view(rho, 2.0, 60.0, 16, 12);
        auto light = test::add_material(v.scene, MaterialKind::Emitter, glm::dvec3(0.0), radiance);
        v.scene.spheres.push_back({c.center, c.radius, light});
        const double geometry = rectangle_mean(v.half_x, v.half_y, [&](double x, double y) {
            const double dx = x - c.center.x, dy = y - c.center.y;
            const double d = std::sqrt(dx * dx + dy * dy + c.center.z * c.center.z);
            return c.center.z / (d * d * d);
        });
        IntegratorOptions options;
        options.sampler = Sampler::Independent;
        test::Rendered r = test::render(v.scene, c.spp, 1, 0, options);
        CHECK(r.stats.nonfinite_samples == 0);
        for (int ch = 0; ch < 3; ++ch) {
            // The camera sees only the floor (the near sphere is outside
            // the view, the far one behind the camera).
            const double expected = rho[ch] * radiance[ch] * c.radius * c.radius * geometry;
            test::MeanWithError m = test::image_mean(r.film, ch);
            INFO("channel " << ch << ": " << m.mean << " +- " << m.standard_error << ", expected "
                            << expected);
            CHECK(std::abs(m.mean - expected) < kSigmas * m.standard_error + 1e-5 * expected);
            CHECK(m.standard_error < 0.01 * expected);
        }
    }
}

TEST_CASE("emitters: sphere lights are a feature switch and an emitter each",
          "[emitters][sphere-light]") {
    Scene scene = test::hexroom(8, 8);
    CHECK_FALSE(analyse_features(scene).sphere_light); // its spheres do not emit
    auto light = test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0), glm::dvec3(5));
    scene.spheres.push_back({{0.1, 0.2, 0.3}, 0.05, light});
    const SceneFeatures f = analyse_features(scene);
    CHECK(f.sphere_light);
    CHECK(f.planar_mirrors); // mirror next-event estimation holds beside other emitters
    CHECK(f.mirror_spheres);
    CHECK_FALSE(f.shadow_culling); // a light outside the culled faces' shadow test
    const DeviceScene flat = flatten_scene(scene, true); // with a hierarchy, which renumbers
    REQUIRE(flat.emitters.size() == 1);
    const WpEmitter& e = flat.emitters[0];
    CHECK(e.kind == WP_EMITTER_SPHERE);
    // It names its sphere by the sphere's number after the reordering.
    REQUIRE(e.sphere < flat.spheres.size());
    CHECK(flat.spheres[e.sphere].material == light);
    CHECK(flat.spheres[e.sphere].center_radius.s[3] == Approx(e.position.s[3]));
    CHECK(flat.emitter_pick > 0.0f);
    CHECK(flat.emitter_pick < 1.0f);
}
