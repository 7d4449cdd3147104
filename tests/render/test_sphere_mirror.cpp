// Next-event estimation through mirror spheres (kernels/mirror_light.h): the
// kernels' reflection point and beam spread against double-precision
// references (a minimisation of the path length, finite differences of
// traced rays), and the estimator against brute force on a light seen only
// in a mirror sphere. Tolerances of the renders are five standard errors of
// the estimates, from the films' own sample variance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "render/device_scene.hpp"
#include "render/planar_mirrors.hpp"
#include "support/kernel_test_util.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_builder.hpp"

using namespace wp;

namespace {

constexpr double kSigmas = 5.0;

// The point m of the sphere (c, r) where x -> m -> y reflects, in double
// precision and by another method than the kernels': the path length
// |x - m| + |m - y| is smallest there among the sphere's points on the arc
// from x's side to y's side (the smallest ellipse with foci x and y that
// touches the sphere touches it there, and its normal bisects the two
// directions); golden-section search over the arc's angle.
glm::dvec3 reflection_point(glm::dvec3 c, double r, glm::dvec3 x, glm::dvec3 y) {
    glm::dvec3 a = glm::normalize(x - c), b = glm::normalize(y - c);
    glm::dvec3 v = b - glm::dot(a, b) * a;
    const double angle = std::atan2(glm::length(v), glm::dot(a, b));
    v = glm::normalize(v);
    auto point = [&](double phi) { return c + r * (std::cos(phi) * a + std::sin(phi) * v); };
    auto path = [&](double phi) {
        glm::dvec3 m = point(phi);
        return glm::length(x - m) + glm::length(y - m);
    };
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double lo = 0.0, hi = angle;
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
        double p = hi - g * (hi - lo), q = lo + g * (hi - lo);
        if (path(p) < path(q))
            hi = q;
        else
            lo = p;
    }
    return point(0.5 * (lo + hi));
}

// The ray x + t w reflected off the sphere (c, r), where it meets the plane
// through `p` with normal `n`; nullopt if it misses the sphere.
std::optional<glm::dvec3> reflect_to_plane(glm::dvec3 c, double r, glm::dvec3 x, glm::dvec3 w,
                                           glm::dvec3 p, glm::dvec3 n) {
    glm::dvec3 f = x - c;
    double b = glm::dot(f, w), disc = b * b - (glm::dot(f, f) - r * r);
    if (disc < 0.0)
        return std::nullopt;
    double t = -b - std::sqrt(disc);
    glm::dvec3 m = x + t * w, normal = (m - c) / r;
    glm::dvec3 out = w - 2.0 * glm::dot(w, normal) * normal;
    return m + (glm::dot(p - m, n) / glm::dot(out, n)) * out;
}

// dA / dw: the area (perpendicular to the reflected ray) that the pencil of
// directions around x -> m covers where it reaches y, per unit solid angle at
// x, by central differences of traced rays; nullopt if a ray of the pencil
// misses the sphere. Towards grazing incidence (cosine `cos_mirror`) the map
// from directions to points bends on a scale of about cos_mirror^2 radians,
// so the step shrinks with it.
std::optional<double> spread_by_tracing(glm::dvec3 c, double r, glm::dvec3 x, glm::dvec3 m,
                                        glm::dvec3 y, double cos_mirror) {
    glm::dvec3 w = glm::normalize(m - x);
    glm::dvec3 out = glm::normalize(y - m);
    glm::dvec3 u = glm::normalize(
        glm::cross(w, std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    glm::dvec3 v = glm::cross(w, u);
    const double h = 1e-4 * std::min(cos_mirror * cos_mirror, 0.01);
    std::optional<glm::dvec3> p[4] = {reflect_to_plane(c, r, x, glm::normalize(w + h * u), y, out),
                                      reflect_to_plane(c, r, x, glm::normalize(w - h * u), y, out),
                                      reflect_to_plane(c, r, x, glm::normalize(w + h * v), y, out),
                                      reflect_to_plane(c, r, x, glm::normalize(w - h * v), y, out)};
    if (!p[0] || !p[1] || !p[2] || !p[3])
        return std::nullopt;
    glm::dvec3 du = (*p[0] - *p[1]) / (2.0 * h), dv = (*p[2] - *p[3]) / (2.0 * h);
    return glm::length(glm::cross(du, dv));
}

} // namespace

TEST_CASE("sphere mirror: the kernels' reflection point and beam spread match double precision",
          "[mirror-nee]") {
    const char* const source = R"CL(
#include "mirror_light.h"
__kernel void sphere_points(float4 sphere, __global const float4* xs, __global const float4* ys,
                            uint count, __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    WpSceneView scene;
    scene.light_area = 1.0f;
    scene.mirror_group_count = 1u; /* one mirror in all */
    scene.mirror_sphere_count = 0u;
    float3 c = sphere.xyz, x = xs[i].xyz, y = ys[i].xyz;
    float r = sphere.w;
    float3 m = (float3)(0.0f);
    int tried = wp_sphere_mirror_tries(c, r, x, y);
    int found = tried && wp_sphere_mirror_point(c, r, x, y, &m);
    float spread = 0.0f;
    if (found) {
        /* With light area 1, one mirror and cos_light 1 the density is dA / dw. */
        float d1 = length(m - x), d2 = length(y - m);
        float cos_mirror = -dot(normalize(m - c), (m - x) / d1);
        spread = wp_sphere_mirror_light_pdf(&scene, 1.0f, d1, d2, cos_mirror, r, 1.0f);
    }
    out[i] = (float4)(m, found ? spread : (tried ? -1.0f : -2.0f));
}
)CL";
    std::mt19937_64 random(21);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const glm::dvec3 c(1.5, -0.5, 2.0);
    const double r = 0.7;
    auto rounded = [](const glm::dvec3& v) { return glm::dvec3(glm::vec3(v)); };
    const cl_uint n = 1u << 13;
    std::vector<cl_float4> xs, ys;
    while (xs.size() < n) {
        glm::dvec3 x =
            rounded(c + 3.0 * glm::dvec3(uniform(random), uniform(random), uniform(random)));
        glm::dvec3 y =
            rounded(c + 3.0 * glm::dvec3(uniform(random), uniform(random), uniform(random)));
        if (glm::length(x - c) < r * 1.01 || glm::length(y - c) < r * 1.01)
            continue;
        xs.push_back(to_float4(x));
        ys.push_back(to_float4(y));
    }
    cl::Kernel kernel(test::program(source, "sphere_points_test.cl"), "sphere_points");
    cl::Buffer x_buffer = test::upload(xs), y_buffer = test::upload(ys),
               out_buffer = test::upload(std::vector<cl_float4>(n));
    test::set_args(kernel, to_float4(c, r), x_buffer, y_buffer, n, out_buffer);
    test::launch(kernel, n);
    std::vector<cl_float4> out = test::download<cl_float4>(out_buffer, n);

    int found = 0, grazing = 0, point_errors = 0, spread_errors = 0, visibility_errors = 0;
    double worst_point = 0.0, worst_spread = 0.0;
    for (cl_uint i = 0; i < n; ++i) {
        glm::dvec3 x(xs[i].s[0], xs[i].s[1], xs[i].s[2]), y(ys[i].s[0], ys[i].s[1], ys[i].s[2]);
        bool tried = out[i].s[3] > -1.5f;
        // The arc search is tried for points less than about 154 degrees apart
        // (a device may round the cosine either way right at the limit).
        const double cosine = glm::dot(x - c, y - c) / (glm::length(x - c) * glm::length(y - c));
        if (std::abs(cosine + 0.9) > 1e-5)
            REQUIRE(tried == (cosine > -0.9));
        if (!tried)
            continue;
        glm::dvec3 m = reflection_point(c, r, x, y);
        glm::dvec3 normal = (m - c) / r;
        double cos_x = glm::dot(normal, glm::normalize(x - m));
        double cos_y = glm::dot(normal, glm::normalize(y - m));
        bool visible = cos_x > 0.0 && cos_y > 0.0;
        bool device_found = out[i].s[3] >= 0.0f;
        if (std::min(std::abs(cos_x), std::abs(cos_y)) < 1e-3) {
            ++grazing; // at the edge of what x or y sees: either answer is right
            continue;
        }
        if (visible != device_found) {
            ++visibility_errors;
            continue;
        }
        if (!visible)
            continue;
        // The spread of the device's formula at the device's point, against
        // traced rays at the exact point (the point's error moves it a little).
        std::optional<double> spread = spread_by_tracing(c, r, x, m, y, cos_x);
        if (!spread) { // the pencil grazes the sphere's outline: no reference
            ++grazing;
            continue;
        }
        double spread_error = std::abs(out[i].s[3] - *spread) / *spread;
        worst_spread = std::max(worst_spread, spread_error);
        // Float rounding (1e-3), and the point's own error (up to 1e-4 radians
        // of the normal, below) moves the incidence cosine by as much, which
        // the tangential term 1 / cos_mirror turns into 1e-4 / cos relative.
        spread_errors += spread_error > 1e-3 + 2.0 * 1e-4 / cos_x;
        glm::dvec3 device_m(out[i].s[0], out[i].s[1], out[i].s[2]);
        double point_error = glm::length(device_m - m) / r;
        worst_point = std::max(worst_point, point_error);
        // 1e-4 radii: the connection's geometry, and so its contribution, is
        // then good to about 1e-4 relative, far below the noise of any render.
        point_errors += point_error > 1e-4;
        ++found;
    }
    INFO(found << " reflections, " << grazing << " grazing; worst point error " << worst_point
               << " radii, worst spread error " << worst_spread);
    CHECK(visibility_errors == 0);
    CHECK(point_errors == 0);
    CHECK(spread_errors == 0);
    CHECK(found > static_cast<int>(n / 10)); // the test has power
    CHECK(grazing < static_cast<int>(n / 100));
}

namespace {

// A small diffuse square at the origin facing +z, a square light at z = 0.5
// beside it facing up, and a mirror sphere above the light: the square sees
// only the light's back directly, so its light comes by way of the sphere
// (and, far weaker, by way of the sphere and the square itself).
Scene light_in_sphere() {
    Scene scene;
    auto patch = test::add_material(scene, MaterialKind::Diffuse, {0.8, 0.6, 0.4});
    auto mirror = test::add_material(scene, MaterialKind::Mirror, {0.9, 0.7, 0.5});
    auto light = test::add_material(scene, MaterialKind::Emitter, glm::dvec3(0.0),
                                    glm::dvec3(10.0, 20.0, 30.0));
    test::add_quad(scene, {-0.1, -0.1, 0}, {0.1, -0.1, 0}, {0.1, 0.1, 0}, {-0.1, 0.1, 0}, patch);
    test::add_quad(scene, {1.0, -0.5, 0.5}, {2.0, -0.5, 0.5}, {2.0, 1.0, 0.5}, {1.0, 1.0, 0.5},
                   light);
    scene.spheres.push_back({{1.2, 0.2, 2.2}, 0.8, mirror});
    scene.camera = test::make_camera({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0.5, 4, 4);
    return scene;
}

} // namespace

TEST_CASE("sphere mirror: a light seen only in a mirror sphere agrees with brute force",
          "[mirror-nee][statistical]") {
    Scene scene = light_in_sphere();
    REQUIRE(find_planar_mirrors(scene).empty());
    REQUIRE(analyse_features(scene).mirror_spheres);
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    test::MeanWithError means[2][3];
    for (bool on : {true, false}) {
        INFO("mirror next-event estimation " << (on ? "on" : "off"));
        options.mirror_next_event = on;
        test::Rendered r = test::render(scene, on ? 512 : 8192, 1, 0, options);
        CHECK(r.stats.nonfinite_samples == 0);
        for (int ch = 0; ch < 3; ++ch) {
            means[on][ch] = test::image_mean(r.film, ch);
            CHECK(means[on][ch].mean > 0.0);
        }
    }
    for (int ch = 0; ch < 3; ++ch) {
        const test::MeanWithError &on = means[1][ch], &off = means[0][ch];
        INFO("channel " << ch << ": on " << on.mean << " +- " << on.standard_error << ", off "
                        << off.mean << " +- " << off.standard_error);
        CHECK(test::sigmas_apart(on, off) < kSigmas);
        CHECK(off.standard_error < 0.05 * off.mean);         // the test has power
        CHECK(on.standard_error * 5.0 < off.standard_error); // at a sixteenth of the samples
    }
}
