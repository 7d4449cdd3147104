// Next-event estimation's triangle lights (kernels/lights.h) on the device:
// the light points wp_sample_light picks, by area and by solid angle
// (WP_LIGHT_SAMPLING), against the density wp_light_pdf gives (the one
// multiple importance sampling weighs a BSDF sample's hit with) by a
// chi-square test, and that density against a double-precision one.
//
// Two lights of areas 2 and 4.5 face a point below them, of one radiance
// (picked by area) or of luminances 1 : 10 (picked by power, area times
// luminance: render/light_pick.hpp, WP_HAS_POWER_LIGHT_PICK). A sample's
// direction is followed in double to the lights' plane, and the point it
// meets is binned on its triangle in the coordinates (u, v) of the square
// that maps onto the triangle with a constant Jacobian (its area): b0 =
// 1 - sqrt(u), b1 = v sqrt(u). A bin's expected count is then
//     N * integral over the bin of p(w(y)) cos_light / d^2 * area du dv,
// p the solid-angle density, integrated by the midpoint rule on a fine
// grid; inside a triangle the integrand is smooth, and no bin straddles an
// edge.
#include "render/device_scene.hpp"
#include "support/chi_square.hpp"
#include "support/double_vector.hpp"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

const char* const kTriangleLightSource = R"CL(
#include "lights.h"

/* Light samples seen from `position` (normal `normal`), with the numbers
 * (u_pick, u, v) of numbers[i]: the direction (w: 1 if sampled) and the
 * sample's own density. */
__kernel void sample(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), float4 position,
                     float4 normal, uint count, __global const float4* numbers,
                     __global float4* directions, __global float* pdfs) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    WpLightSample s;
    int ok = wp_sample_light(&scene, position.xyz, position.xyz, position.xyz, 0, normal.xyz,
                             numbers[i].x, numbers[i].y, numbers[i].z, &s);
    directions[i] = (float4)(ok ? s.direction : (float3)(0.0f), ok ? 1.0f : 0.0f);
    pdfs[i] = ok ? s.pdf : 0.0f;
}

/* wp_light_pdf from `position` of the point points[i].xyz on triangle
 * number points[i].w. */
__kernel void density(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), float4 position,
                      uint count, __global const float4* points, __global float* pdfs) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    WpTriangle light = scene.triangles[(uint)points[i].w];
    pdfs[i] = wp_light_pdf(&scene, &light, position.xyz, points[i].xyz);
}
)CL";

constexpr double kPi = 3.14159265358979323846;

// With `unequal`, the second light is 10 times as bright (in luminance) as
// the first, so that the pick by power differs from the pick by area.
wp::Scene two_lights(bool unequal) {
    wp::Scene scene;
    wp::Material emitter;
    emitter.kind = wp::MaterialKind::Emitter;
    emitter.emission = {4, 3, 2};
    scene.materials.push_back(emitter);
    emitter.emission *= 10.0;
    scene.materials.push_back(emitter);
    auto triangle = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, std::uint32_t material) {
        wp::Triangle t;
        t.v = {a, b, c};
        t.material = material;
        scene.triangles.push_back(t);
    };
    triangle({-1, 4, -1}, {1, 4, -1}, {-1, 4, 1}, 0);            // area 2, facing -y
    triangle({1, 4, -1}, {4, 4, 2}, {1, 4, 2}, unequal ? 1 : 0); // area 4.5, facing -y
    scene.camera.width = 1;
    scene.camera.height = 1;
    return scene;
}

double triangle_area(const WpTriangle& t) {
    return 0.5 * length(cross(triangle_vertex(t, 1) - triangle_vertex(t, 0),
                              triangle_vertex(t, 2) - triangle_vertex(t, 0)));
}

// The solid angle triangle t subtends from x (Van Oosterom and Strackee), in double.
double solid_angle(const WpTriangle& t, D3 x) {
    const D3 a = triangle_vertex(t, 0) - x, b = triangle_vertex(t, 1) - x,
             c = triangle_vertex(t, 2) - x;
    const double la = length(a), lb = length(b), lc = length(c);
    const double numerator = std::fabs(dot(a, cross(b, c)));
    const double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    double omega = 2.0 * std::atan2(numerator, denominator);
    return omega < 0.0 ? omega + 2.0 * kPi : omega;
}

struct Setup {
    wp::Scene scene;
    DeviceScene flat;
    WpFrame frame{};
    DeviceBuffers buffers;
    std::string options;
    // Per light, 1 / the density per unit area of the pick and the point on
    // it, in double: the total area by area; by power, the total of area x
    // luminance over the light's luminance.
    double spread[2] = {0.0, 0.0};

    Setup(bool solid_angle_sampling, bool unequal)
        : scene(two_lights(unequal)), flat(flatten_scene(scene)) {
        SceneFeatures features = analyse_features(scene);
        CHECK(features.power_light_pick == unequal);
        features.fixed_counts = false;
        double luminance[2], total = 0.0;
        for (int k = 0; k < 2; ++k) {
            const glm::dvec3 e = scene.materials[scene.triangles[std::size_t(k)].material].emission;
            luminance[k] = unequal ? 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z : 1.0;
            total += triangle_area(flat.triangles[std::size_t(k)]) * luminance[k];
        }
        for (int k = 0; k < 2; ++k)
            spread[k] = total / luminance[k];
        options = features.build_options() +
                  (solid_angle_sampling ? " -D WP_LIGHT_SAMPLING=1" : " -D WP_LIGHT_SAMPLING=0");
        buffers = allocate_device_buffers(device().context, flat, 1, 1);
        frame.triangle_count = cl_uint(flat.triangles.size());
        frame.light_count = cl_uint(flat.lights.size());
        frame.light_area = flat.light_area;
    }

    cl::Kernel kernel(const char* name) const {
        cl::Kernel k(program(kTriangleLightSource, "triangle_light_test.cl", options), name);
        k.setArg(0, frame);
        return k;
    }
};

// The double-precision solid-angle density of the direction from x to the
// point y of light number k, `t`: uniform by area (d^2 / (cos_light spread)) or
// uniform in the triangle's solid angle, each triangle chosen by area or power.
double reference_pdf(const Setup& s, int k, const WpTriangle& t, D3 x, D3 y, bool by_solid_angle) {
    const double total = s.spread[k];
    if (by_solid_angle)
        return triangle_area(t) / total / solid_angle(t, x);
    const D3 to_light = y - x;
    const double d = length(to_light);
    const D3 n = normalize(cross(triangle_vertex(t, 1) - triangle_vertex(t, 0),
                                 triangle_vertex(t, 2) - triangle_vertex(t, 0)));
    return d * d / (-dot(n, to_light / d) * total);
}

// The chi-square test of the light samples against wp_light_pdf, and that
// density against the double-precision one.
void check_samples_follow_pdf(bool unequal) {
    for (const bool by_solid_angle : {false, true}) {
        INFO((by_solid_angle ? "solid-angle sampling" : "area sampling"));
        const Setup setup(by_solid_angle, unequal);
        REQUIRE(setup.flat.lights.size() == 2);
        const D3 x(0.3, 0.5, -0.2);
        const cl_float4 position = to_float4(x), normal = to_float4(D3(0, 1, 0));
        const WpTriangle lights[2] = {setup.flat.triangles[0], setup.flat.triangles[1]};

        // The samples.
        const std::size_t count = 100000;
        std::mt19937 rng(31);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<cl_float4> numbers(count);
        for (cl_float4& n : numbers)
            n = {{unit(rng), unit(rng), unit(rng), 0.0f}};
        cl::Kernel sample = setup.kernel("sample");
        const cl::Buffer in = upload(numbers),
                         directions_out = upload(std::vector<cl_float4>(count)),
                         pdfs_out = upload(std::vector<float>(count));
        cl_uint next = bind_scene_buffers(sample, 1, setup.buffers);
        sample.setArg(next++, position);
        sample.setArg(next++, normal);
        sample.setArg(next++, cl_uint(count));
        sample.setArg(next++, in);
        sample.setArg(next++, directions_out);
        sample.setArg(next++, pdfs_out);
        launch(sample, count);
        const auto directions = download<cl_float4>(directions_out, count);
        const auto pdfs = download<float>(pdfs_out, count);

        // Bin each sample where its direction meets a light, in double.
        const int bins = 8; // per side of each triangle's square
        std::vector<double> observed(2 * bins * bins, 0.0);
        std::size_t missed = 0, bad_pdf = 0;
        for (std::size_t i = 0; i < count; ++i) {
            if (directions[i].s[3] != 1.0f) {
                ++missed;
                continue;
            }
            const D3 wi = normalize(from_float4(directions[i]));
            const D3 y = x + ((4.0 - x.y) / wi.y) * wi;
            int found = -1;
            double u = 0.0, v = 0.0;
            for (int k = 0; k < 2 && found < 0; ++k) {
                const D3 a = triangle_vertex(lights[k], 0), b = triangle_vertex(lights[k], 1),
                         c = triangle_vertex(lights[k], 2);
                const double twice = length(cross(b - a, c - a));
                const double b1 = dot(cross(c - y, a - y), normalize(cross(b - a, c - a))) / twice;
                const double b2 = dot(cross(a - y, b - y), normalize(cross(b - a, c - a))) / twice;
                const double b0 = 1.0 - b1 - b2;
                const double slack = 1e-5;
                if (b0 < -slack || b1 < -slack || b2 < -slack)
                    continue;
                found = k;
                const double sq = std::max(1.0 - b0, 1e-12);
                u = sq * sq;
                v = b1 / sq;
                if (!(std::fabs(pdfs[i] - reference_pdf(setup, k, lights[k], x, y,
                                                        by_solid_angle)) <= 1e-3 * pdfs[i]))
                    ++bad_pdf;
            }
            if (found < 0) {
                ++missed;
                continue;
            }
            const int a = std::clamp(int(u * bins), 0, bins - 1);
            const int b = std::clamp(int(v * bins), 0, bins - 1);
            observed[std::size_t((found * bins + a) * bins + b)] += 1.0;
        }
        CHECK(missed == 0);
        CHECK(bad_pdf == 0);

        // The kernels' density on a fine grid of each bin, and the expected counts.
        const int fine = 8; // midpoints per bin side
        std::vector<cl_float4> points;
        std::vector<double> jacobian; // cos_light / d^2 * area, in double
        for (int k = 0; k < 2; ++k) {
            const D3 a = triangle_vertex(lights[k], 0), b = triangle_vertex(lights[k], 1),
                     c = triangle_vertex(lights[k], 2);
            const D3 n = normalize(cross(b - a, c - a));
            for (int i = 0; i < bins * fine; ++i)
                for (int j = 0; j < bins * fine; ++j) {
                    const double u = (i + 0.5) / (bins * fine), v = (j + 0.5) / (bins * fine);
                    const double su = std::sqrt(u);
                    const D3 y = (1.0 - su) * a + v * su * b + (1.0 - v) * su * c;
                    const D3 to_light = y - x;
                    const double d = length(to_light);
                    points.push_back(to_float4(y, float(k)));
                    jacobian.push_back(-dot(n, to_light / d) / (d * d) * triangle_area(lights[k]));
                }
        }
        cl::Kernel density = setup.kernel("density");
        const cl::Buffer points_in = upload(points),
                         density_out = upload(std::vector<float>(points.size()));
        next = bind_scene_buffers(density, 1, setup.buffers);
        density.setArg(next++, position);
        density.setArg(next++, cl_uint(points.size()));
        density.setArg(next++, points_in);
        density.setArg(next++, density_out);
        launch(density, points.size());
        const auto density_at = download<float>(density_out, points.size());

        std::vector<double> expected(observed.size(), 0.0);
        double total_probability = 0.0;
        std::size_t bad_density = 0;
        const double cell = 1.0 / double(bins * fine * bins * fine);
        for (std::size_t p = 0; p < points.size(); ++p) {
            const int k = int(p / std::size_t(bins * fine * bins * fine));
            const std::size_t within = p % std::size_t(bins * fine * bins * fine);
            const int i = int(within / std::size_t(bins * fine)),
                      j = int(within % std::size_t(bins * fine));
            const D3 y = from_float4(points[p]);
            const double reference = reference_pdf(setup, k, lights[k], x, y, by_solid_angle);
            if (!(std::fabs(density_at[p] - reference) <= 1e-4 * reference))
                ++bad_density;
            const double probability = density_at[p] * jacobian[p] * cell;
            expected[std::size_t((k * bins + i / fine) * bins + j / fine)] +=
                probability * double(count);
            total_probability += probability;
        }
        CHECK(bad_density == 0);
        // The density integrates to 1 over both lights (every direction
        // towards them is sampled: they face the point, above its horizon).
        CHECK(total_probability == Approx(1.0).epsilon(1e-3));
        const ChiSquare test = chi_square(observed, expected);
        INFO("chi-square " << test.statistic << " with " << test.dof
                           << " dof, p = " << test.p_value);
        CHECK(test.outside == 0);
        CHECK(test.p_value > 1e-3);
    }
}

} // namespace

TEST_CASE("triangle lights: samples follow wp_light_pdf by area and by solid angle (chi-square)",
          "[kernels][lights][statistical]") {
    check_samples_follow_pdf(false);
}

TEST_CASE("triangle lights: the power pick's samples follow wp_light_pdf with unequal lights "
          "(chi-square)",
          "[kernels][lights][light-pick][statistical]") {
    check_samples_follow_pdf(true);
}
