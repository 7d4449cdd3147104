// The sphere light's cone sampling (kernels/lights/sphere.h) on the device:
// its directions against the uniform density on the cone by a chi-square
// test, each direction's distance to the sphere against a double-precision
// ray-sphere intersection, and the density against 1 / (2 pi (1 - cos
// theta_max)) in double, for a near, a far and a tiny sphere, and from inside.
#include "support/chi_square.hpp"
#include "support/kernel_test_util.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

using namespace wp;
using namespace wp::test;

namespace {

const char* const kSphereSource = R"CL(
#include "lights/sphere.h"

__kernel void sample(float4 point, float4 sphere, uint count, __global const float2* numbers,
                     __global float4* directions, __global float2* distance_pdf) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float3 wi;
    float t = 0.0f, pdf = 0.0f;
    int ok = wp_sample_sphere_light(point.xyz, sphere, numbers[i].x, numbers[i].y, &wi, &t, &pdf);
    directions[i] = (float4)(wi, ok ? 1.0f : 0.0f);
    distance_pdf[i] = (float2)(t, ok ? pdf : 0.0f);
    if (i == 0u) /* the density the MIS weight takes, from the same point */
        distance_pdf[count] = (float2)(wp_sphere_light_pdf(point.xyz, sphere), 0.0f);
}
)CL";

constexpr double kPi = 3.14159265358979323846;

struct Drawn {
    std::vector<cl_float4> directions;
    std::vector<cl_float2> distance_pdf; // one more: the pdf function's value
};

Drawn draw(const glm::dvec3& p, const glm::dvec3& center, double radius, std::size_t count) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<cl_float2> numbers(count);
    for (cl_float2& n : numbers)
        n = {{unit(rng), unit(rng)}};
    cl::Kernel kernel(program(kSphereSource, "sphere_light_test.cl"), "sample");
    const cl_float4 point = {{float(p.x), float(p.y), float(p.z), 0.0f}};
    const cl_float4 sphere = {{float(center.x), float(center.y), float(center.z), float(radius)}};
    const cl::Buffer in = upload(numbers), directions = upload(std::vector<cl_float4>(count)),
                     distance_pdf = upload(std::vector<cl_float2>(count + 1));
    set_args(kernel, point, sphere, static_cast<cl_uint>(count), in, directions, distance_pdf);
    launch(kernel, count);
    return {download<cl_float4>(directions, count), download<cl_float2>(distance_pdf, count + 1)};
}

} // namespace

TEST_CASE("sphere light: cone samples are uniform in the cone and land on the sphere",
          "[kernels][emitters][statistical]") {
    struct Case {
        const char* what;
        glm::dvec3 p, center;
        double radius;
    };
    const Case cases[] = {
        {"near (d = 1.5 r)", {0.1, -0.2, 0.3}, {1.0, 1.3, -0.6}, 1.2},
        {"far (d = 40 r)", {2.0, 0.0, 1.0}, {-3.0, 7.0, 4.0}, 0.23},
        {"tiny (d = 5e4 r): 1 - cos theta_max below float's epsilon", {0, 0, 0}, {0, 0, 10}, 2e-4},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        const std::size_t count = 200000;
        const Drawn drawn = draw(c.p, c.center, c.radius, count);
        // In double: the cone's axis and 1 - cos theta_max.
        const glm::dvec3 to_center = c.center - c.p;
        const double d = glm::length(to_center);
        const glm::dvec3 axis = to_center / d;
        const double sin2 = c.radius * c.radius / (d * d);
        const double one_minus_cos = sin2 / (1.0 + std::sqrt(1.0 - sin2));
        const double pdf = 1.0 / (2.0 * kPi * one_minus_cos);
        CHECK(drawn.distance_pdf[count].s[0] == Approx(pdf).epsilon(1e-5));
        // Bins: 10 of (1 - cos theta) / (1 - cos theta_max), each uniform, by
        // 12 of phi around the axis (from a fixed perpendicular).
        glm::dvec3 x = glm::normalize(
            glm::cross(axis, std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        const glm::dvec3 y = glm::cross(axis, x);
        const int bins_theta = 10, bins_phi = 12;
        std::vector<double> observed(bins_theta * bins_phi, 0.0),
            expected(observed.size(), double(count) / double(observed.size()));
        std::size_t failed = 0, off_sphere = 0, bad_pdf = 0;
        for (std::size_t i = 0; i < count; ++i) {
            if (drawn.directions[i].s[3] != 1.0f) {
                ++failed;
                continue;
            }
            const glm::dvec3 wi = glm::normalize(glm::dvec3(
                drawn.directions[i].s[0], drawn.directions[i].s[1], drawn.directions[i].s[2]));
            const double cos_theta = glm::dot(wi, axis);
            // 1 - cos theta from the perpendicular part (no cancellation).
            const glm::dvec3 perpendicular = wi - cos_theta * axis;
            const double s2 = glm::dot(perpendicular, perpendicular);
            const double f = s2 / (1.0 + cos_theta) / one_minus_cos;
            double phi = std::atan2(glm::dot(wi, y), glm::dot(wi, x));
            phi = phi < 0.0 ? phi + 2.0 * kPi : phi;
            const int a = std::min(bins_theta - 1, static_cast<int>(f * bins_theta));
            const int b = std::min(bins_phi - 1, static_cast<int>(phi / (2.0 * kPi) * bins_phi));
            if (f > 1.0 + 1e-3) {
                ++off_sphere; // outside the cone
                continue;
            }
            observed[static_cast<std::size_t>(a * bins_phi + b)] += 1.0;
            // The distance reported is where the ray meets the sphere: the
            // near root of |p + t wi - c| = r, in double.
            const double along = glm::dot(to_center, wi);
            const double disc = c.radius * c.radius - (d * d - along * along);
            const double t = along - std::sqrt(std::max(0.0, disc));
            if (!(std::abs(drawn.distance_pdf[i].s[0] - t) <= 1e-3 * c.radius + 1e-5 * d))
                ++off_sphere;
            if (!(std::abs(drawn.distance_pdf[i].s[1] - pdf) <= 1e-5 * pdf))
                ++bad_pdf;
        }
        CHECK(failed == 0);
        CHECK(off_sphere == 0);
        CHECK(bad_pdf == 0);
        const ChiSquare test = chi_square(observed, expected);
        INFO("chi-square " << test.statistic << " with " << test.dof
                           << " dof, p = " << test.p_value);
        CHECK(test.p_value > 1e-3);
    }
}

TEST_CASE("sphere light: nothing is sampled from inside or on the sphere", "[kernels][emitters]") {
    for (const glm::dvec3 p : {glm::dvec3(0.2, 0.1, 0.0), glm::dvec3(1.0, 0.0, 0.0)}) {
        const Drawn drawn = draw(p, {0, 0, 0}, 1.0, 64);
        for (std::size_t i = 0; i < 64; ++i)
            CHECK(drawn.directions[i].s[3] == 0.0f);
        CHECK(drawn.distance_pdf[64].s[0] == 0.0f);
    }
}
