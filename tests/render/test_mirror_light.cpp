// Next-event estimation through planar mirrors (kernels/mirror_light.h):
// against the closed form of a light seen only in a mirror, against the
// estimator without it (brute force), and its mirror point against a
// double-precision host reference. Tolerances are five standard errors of
// the estimates, from the films' own sample variance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "render/device_scene.hpp"
#include "render/planar_mirrors.hpp"
#include "support/form_factor.hpp"
#include "support/kernel_test_util.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

constexpr double kSigmas = 5.0;

using test::rectangle_form_factor;

// A small diffuse square at the origin facing +z, a mirror ceiling at z = h
// (two triangles), and a square light at z = c < h beside the origin facing
// up, towards the mirror: the square sees only the light's back directly,
// so all its light comes by way of the mirror, from the light's image at
// z = 2h - c facing down.
struct MirrorScene {
    Scene scene;
    glm::dvec3 rho{0.8, 0.6, 0.4}, mirror{0.9, 0.7, 0.5}, emission{10.0, 20.0, 30.0};
    double x0 = 1.0, x1 = 2.0, y0 = -0.5, y1 = 1.0, c = 0.5, h = 2.0;
    double expected(int channel) const {
        return mirror[channel] * rho[channel] * emission[channel] *
               rectangle_form_factor(x0, x1, y0, y1, 2.0 * h - c);
    }
};

MirrorScene light_in_mirror() {
    MirrorScene s;
    auto patch = test::add_material(s.scene, MaterialKind::Diffuse, s.rho);
    auto mirror = test::add_material(s.scene, MaterialKind::Mirror, s.mirror);
    auto light = test::add_material(s.scene, MaterialKind::Emitter, glm::dvec3(0.0), s.emission);
    // The receiver: small, so that its own image in the mirror adds light of
    // order rho * (0.2)^2 / (pi (2h)^2), 1e-4 relative, far below the error bars.
    test::add_quad(s.scene, {-0.1, -0.1, 0}, {0.1, -0.1, 0}, {0.1, 0.1, 0}, {-0.1, 0.1, 0}, patch);
    test::add_quad(s.scene, {-10, -10, s.h}, {-10, 10, s.h}, {10, 10, s.h}, {10, -10, s.h}, mirror);
    // Counter-clockwise from above: the light's normal is +z, towards the mirror.
    test::add_quad(s.scene, {s.x0, s.y0, s.c}, {s.x1, s.y0, s.c}, {s.x1, s.y1, s.c},
                   {s.x0, s.y1, s.c}, light);
    // A narrow view of the patch's centre from above.
    s.scene.camera = test::make_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0.5, 4, 4);
    return s;
}

IntegratorOptions with_mirror_nee(bool on) {
    IntegratorOptions options;
    options.mirror_next_event = on;
    return options;
}

} // namespace

TEST_CASE("mirror light: the light seen only in a planar mirror gives R rho Le F of its image",
          "[mirror-nee][statistical]") {
    MirrorScene s = light_in_mirror();
    REQUIRE(find_planar_mirrors(s.scene).size() == 1);
    REQUIRE(find_planar_mirrors(s.scene)[0].triangles.size() == 2);
    test::MeanWithError means[2][3];
    for (bool on : {true, false}) {
        INFO("mirror next-event estimation " << (on ? "on" : "off"));
        test::Rendered r = test::render(s.scene, on ? 1024 : 8192, 1, 0, with_mirror_nee(on));
        CHECK(r.stats.nonfinite_samples == 0);
        for (int ch = 0; ch < 3; ++ch) {
            test::MeanWithError m = test::image_mean(r.film, ch);
            means[on][ch] = m;
            INFO("channel " << ch << ": " << m.mean << " +- " << m.standard_error << ", expected "
                            << s.expected(ch));
            CHECK(std::abs(m.mean - s.expected(ch)) < kSigmas * m.standard_error);
            CHECK(m.standard_error < (on ? 0.005 : 0.03) * s.expected(ch)); // the test has power
        }
    }
    // On against off (brute force): within 5 combined standard errors, and
    // the mirrored light sample cuts the error by far.
    for (int ch = 0; ch < 3; ++ch) {
        const test::MeanWithError &on = means[1][ch], &off = means[0][ch];
        INFO("channel " << ch << ": on " << on.mean << " +- " << on.standard_error << ", off "
                        << off.mean << " +- " << off.standard_error);
        CHECK(test::sigmas_apart(on, off) < kSigmas);
        CHECK(on.standard_error * 5.0 < off.standard_error); // at an eighth of the samples
    }
}

TEST_CASE("mirror light: the hexroom with and without it agrees within noise, block by block",
          "[mirror-nee][statistical]") {
    // Unbiasedness and the weights: the multiple importance sampling weights
    // of the two ways to find light through the mirror wall sum to 1, or the
    // mirror's caustic comes out too bright or too dark here. Independent
    // samples, so that the film's sample variance is an honest error bar.
    Scene scene = test::hexroom(32, 32);
    REQUIRE(find_planar_mirrors(scene).size() == 1); // the mirror wall
    REQUIRE(analyse_features(scene).mirror_spheres); // and the mirror sphere
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    options.mirror_next_event = true;
    test::Rendered on = test::render(scene, 512, 3, 0, options);
    options.mirror_next_event = false;
    test::Rendered off = test::render(scene, 1024, 4, 0, options);
    const test::BlockComparison blocks = test::compare_blocks(on.film, off.film, 8, kSigmas);
    for (int ch = 0; ch < 3; ++ch) {
        test::MeanWithError a = test::image_mean(on.film, ch), b = test::image_mean(off.film, ch);
        INFO("channel " << ch << ": on " << a.mean << " +- " << a.standard_error << ", off "
                        << b.mean << " +- " << b.standard_error);
        CHECK(test::sigmas_apart(a, b) < kSigmas);
        CHECK(a.standard_error < 0.01 * a.mean); // the test has power
    }
    INFO("largest block deviation " << blocks.worst_sigmas << " combined sigma, "
                                    << blocks.worst_where);
    CHECK(blocks.outside == 0);
}

TEST_CASE("mirror light: beside a sphere light and a point light, on and off agree within noise",
          "[mirror-nee][emitters][statistical]") {
    // The mirrored light sample is an estimator of its own, of the emissive
    // triangles' light by way of a mirror, so it holds beside lights of other
    // kinds: the hexroom with a sphere light and a point light (whose light by
    // way of the mirrors the paths find themselves) renders the same with it
    // as without. One of the ceiling light's triangles is brighter, so the
    // triangles are picked by power and the mirrored sample's density is the
    // power pick's.
    Scene scene = test::hexroom(24, 24);
    auto bright = test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0),
                                     glm::dvec3(300, 250, 200));
    Triangle light = scene.triangles.back();
    light.material = bright;
    scene.triangles.set(scene.triangles.size() - 1, light);
    scene.spheres.push_back({{4.0, -2.0, 2.0}, 0.3, bright});
    Emitter point;
    point.kind = EmitterKind::Point;
    point.position = {8.0, 3.0, 0.0};
    point.value = glm::dvec3(40.0, 60.0, 80.0);
    scene.emitters.push_back(point);
    const SceneFeatures features = analyse_features(scene);
    REQUIRE(features.planar_mirrors);
    REQUIRE(features.mirror_spheres);
    REQUIRE(features.sphere_light);
    REQUIRE(features.point_light);
    REQUIRE(features.power_light_pick);
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    options.mirror_next_event = true;
    test::Rendered on = test::render(scene, 512, 3, 0, options);
    options.mirror_next_event = false;
    test::Rendered off = test::render(scene, 1024, 4, 0, options);
    CHECK(on.stats.nonfinite_samples == 0);
    const test::BlockComparison blocks = test::compare_blocks(on.film, off.film, 8, kSigmas);
    for (int ch = 0; ch < 3; ++ch) {
        test::MeanWithError a = test::image_mean(on.film, ch), b = test::image_mean(off.film, ch);
        INFO("channel " << ch << ": on " << a.mean << " +- " << a.standard_error << ", off "
                        << b.mean << " +- " << b.standard_error << ": " << test::sigmas_apart(a, b)
                        << " sigma");
        CHECK(test::sigmas_apart(a, b) < kSigmas);
        CHECK(a.standard_error < 0.01 * a.mean); // the test has power
    }
    INFO("largest block deviation " << blocks.worst_sigmas << " combined sigma, "
                                    << blocks.worst_where);
    CHECK(blocks.outside == 0);
}

TEST_CASE("mirror light: the kernels' mirror point matches a double-precision reference",
          "[mirror-nee]") {
    const char* const source = R"CL(
#include "mirror_light.h"
__kernel void mirror_points(WpMirrorGroup group, __global const WpTriangle* triangles, uint count,
                            __global const float4* xs, __global const float4* ys,
                            __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    WpSceneView scene;
    scene.mirror_triangles = triangles;
    float3 m = (float3)(0.0f);
    uint k = 0u;
    int inside = wp_mirror_connect(&scene, &group, xs[i].xyz, ys[i].xyz, &m, &k);
    out[i] = (float4)(m, inside ? (float)k : -1.0f);
}
)CL";
    // A planar hexagon (a fan of 4 triangles) in a tilted plane, away from the origin.
    std::mt19937_64 random(12);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const glm::dvec3 normal = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const glm::dvec3 t = glm::normalize(glm::cross(normal, glm::dvec3(1, 0, 0)));
    const glm::dvec3 b = glm::cross(normal, t);
    const glm::dvec3 centre(3.0, -2.0, 1.5);
    std::vector<glm::dvec3> corners;
    for (int i = 0; i < 6; ++i) {
        double a = i * M_PI / 3.0, r = i % 2 ? 2.0 : 1.5;
        corners.push_back(centre + r * std::cos(a) * t + r * std::sin(a) * b);
    }
    std::vector<std::array<glm::dvec3, 3>> fan;
    for (int i = 1; i < 5; ++i)
        fan.push_back({corners[0], corners[i], corners[i + 1]});
    // Rounded to float as the device holds them, and the reference is given those.
    auto rounded = [](const glm::dvec3& v) { return glm::dvec3(glm::vec3(v)); };
    std::vector<WpTriangle> triangles;
    for (auto& tri : fan) {
        for (auto& v : tri)
            v = rounded(v);
        WpTriangle w{};
        w.v0 = to_float4(tri[0]);
        w.v1 = to_float4(tri[1]);
        w.v2 = to_float4(tri[2]);
        triangles.push_back(w);
    }
    const double offset = glm::dot(normal, rounded(centre));
    WpMirrorGroup group{};
    group.plane = to_float4(normal, offset);
    group.first = 0;
    group.count = static_cast<cl_uint>(triangles.size());
    // The reference takes the plane as the device holds it, too.
    const glm::dvec3 device_normal(group.plane.s[0], group.plane.s[1], group.plane.s[2]);
    const double device_offset = group.plane.s[3];

    const cl_uint n = 1u << 14;
    std::vector<cl_float4> xs, ys;
    for (cl_uint i = 0; i < n; ++i) {
        // Points within 4 of the centre, on either side (a quarter on opposite sides).
        glm::dvec3 x =
            rounded(centre + 4.0 * glm::dvec3(uniform(random), uniform(random), uniform(random)));
        glm::dvec3 y =
            rounded(centre + 4.0 * glm::dvec3(uniform(random), uniform(random), uniform(random)));
        xs.push_back(to_float4(x));
        ys.push_back(to_float4(y));
    }
    cl::Kernel kernel(test::program(source, "mirror_points_test.cl"), "mirror_points");
    cl::Buffer tri_buffer = test::upload(triangles), x_buffer = test::upload(xs),
               y_buffer = test::upload(ys), out_buffer = test::upload(std::vector<cl_float4>(n));
    test::set_args(kernel, group, tri_buffer, n, x_buffer, y_buffer, out_buffer);
    test::launch(kernel, n);
    std::vector<cl_float4> out = test::download<cl_float4>(out_buffer, n);

    auto edge_distance = [&](const glm::dvec3& p) {
        double d = 1e300;
        for (const auto& tri : fan)
            for (int e = 0; e < 3; ++e) {
                glm::dvec3 a = tri[e], ab = tri[(e + 1) % 3] - a;
                double s = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
                d = std::min(d, glm::length(p - (a + s * ab)));
            }
        return d;
    };
    int inside = 0, boundary = 0, mismatched = 0;
    double worst = 0.0;
    for (cl_uint i = 0; i < n; ++i) {
        glm::dvec3 x(xs[i].s[0], xs[i].s[1], xs[i].s[2]), y(ys[i].s[0], ys[i].s[1], ys[i].s[2]);
        std::optional<MirrorPoint> ref = mirror_point(device_normal, device_offset, fan, x, y);
        bool device_inside = out[i].s[3] >= 0.0f;
        glm::dvec3 m(out[i].s[0], out[i].s[1], out[i].s[2]);
        if (ref && device_inside) {
            ++inside;
            // The point itself: a few float ulps of the coordinates (about 8), more
            // when x or y lies next to the plane (the crossing is then steep).
            double sx = std::abs(glm::dot(device_normal, x) - device_offset);
            double sy = std::abs(glm::dot(device_normal, y) - device_offset);
            double tolerance = 1e-5 * (1.0 + glm::length(x - y) / std::min(sx + sy, 1.0));
            double error = glm::length(m - ref->point);
            worst = std::max(worst, error / tolerance);
            if (error > tolerance)
                ++mismatched;
        } else if (ref.has_value() != device_inside) {
            // Inside for one and outside for the other: only next to the outline.
            if (ref && edge_distance(ref->point) < 1e-5)
                ++boundary;
            else if (!ref && device_inside && edge_distance(m) < 1e-5)
                ++boundary;
            else
                ++mismatched;
        }
    }
    INFO(inside << " inside, " << boundary << " on the outline, worst error " << worst
                << " of its tolerance");
    CHECK(mismatched == 0);
    CHECK(inside > static_cast<int>(n / 20)); // the test has power
    CHECK(boundary < 10);
}
