// sampling.h on the device: cosine-weighted hemisphere directions and uniform
// triangle points, checked against analytic moments (within 5 standard errors
// taken from the sample variance) and chi-square uniformity tests.
#include "render/device_scene.hpp"
#include "rng.h"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

using namespace wp::test;

namespace {

// Built once per sampler (WP_SAMPLER); with WP_ALONG_SAMPLES the numbers are
// the samples of one pixel (stratified by the Sobol sampler), else sample 0 of
// many pixels.
const char* const kSamplingSource = R"CL(
#include "rng.h"
#include "sampling.h"
#ifdef WP_ALONG_SAMPLES
#define WP_KEY(i) 0u, (i)
#else
#define WP_KEY(i) (i), 0u
#endif

__kernel void cosine_samples(float4 n, uint seed, uint count, __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float u1 = wp_random(seed, WP_KEY(i), 0u, WP_DIM_BSDF_U);
    float u2 = wp_random(seed, WP_KEY(i), 0u, WP_DIM_BSDF_V);
    out[i] = (float4)(wp_sample_cosine_hemisphere(n.xyz, u1, u2), 0.0f);
}

__kernel void sphere_samples(uint seed, uint count, __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float u1 = wp_random(seed, WP_KEY(i), 0u, WP_DIM_LIGHT_U);
    float u2 = wp_random(seed, WP_KEY(i), 0u, WP_DIM_LIGHT_V);
    out[i] = (float4)(wp_sample_uniform_sphere(u1, u2), 0.0f);
}

__kernel void atan2_of(uint count, __global const float2* yx, __global float* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    out[i] = wp_atan2(yx[i].x, yx[i].y);
}

__kernel void sincos_2pi(uint count, __global const uint* k, __global float2* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float s, c;
    wp_sincos_2pi((float)k[i] * (1.0f / 16777216.0f), &s, &c); /* u = k / 2^24, as rng.h's */
    out[i] = (float2)(s, c);
}

__kernel void triangle_samples(float4 p0, float4 p1, float4 p2, uint seed, uint count,
                               __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float u1 = wp_random(seed, WP_KEY(i), 0u, WP_DIM_LIGHT_U);
    float u2 = wp_random(seed, WP_KEY(i), 0u, WP_DIM_LIGHT_V);
    out[i] = (float4)(wp_sample_triangle(p0.xyz, p1.xyz, p2.xyz, u1, u2), 0.0f);
}
)CL";

constexpr cl_uint kSamples = 1u << 20;

// The samplers the uniformity tests run on: independent, Sobol across pixels,
// Sobol along one pixel's samples.
std::string sampler_options() {
    return GENERATE(as<std::string>{}, "-D WP_SAMPLER=0", "-D WP_SAMPLER=1",
                    "-D WP_SAMPLER=1 -D WP_ALONG_SAMPLES");
}

// Mean and standard error of a sample.
struct Moment {
    double sum = 0.0, sum_squares = 0.0;
    std::size_t n = 0;

    void add(double x) {
        sum += x;
        sum_squares += x * x;
        ++n;
    }
    double mean() const { return sum / double(n); }
    double variance() const {
        double m = mean();
        return (sum_squares - double(n) * m * m) / double(n - 1);
    }
    double standard_error() const { return std::sqrt(variance() / double(n)); }
};

void check_mean(const char* what, const Moment& m, double expected) {
    INFO(what << ": mean " << m.mean() << ", expected " << expected << ", standard error "
              << m.standard_error());
    CHECK(std::fabs(m.mean() - expected) <= 5.0 * m.standard_error() + 1e-12);
}

// Pearson's chi-square statistic of counts against a uniform expectation.
double chi_square(const std::vector<std::size_t>& counts, std::size_t total) {
    double expected = double(total) / double(counts.size()), statistic = 0.0;
    for (std::size_t c : counts)
        statistic += (double(c) - expected) * (double(c) - expected) / expected;
    return statistic;
}

// A statistic for `dof` degrees of freedom this far above its mean is a
// more-than-5-sigma event (the chi-square's variance is 2 dof).
double chi_square_limit(std::size_t dof) {
    return double(dof) + 5.0 * std::sqrt(2.0 * double(dof));
}

std::vector<cl_float4> run_samples(cl::Kernel& kernel) {
    cl::Buffer out = upload(std::vector<cl_float4>(kSamples));
    kernel.setArg(kernel.getInfo<CL_KERNEL_NUM_ARGS>() - 1, out);
    launch(kernel, kSamples);
    return download<cl_float4>(out, kSamples);
}

} // namespace

TEST_CASE("wp_sample_uniform_sphere is uniform on the sphere (chi-square against 1 / 4 pi)",
          "[cl][sampling][statistical]") {
    // The constant emitter's light sample (kernels/lights.h): its pdf
    // 1 / (4 pi) is what multiple importance sampling weighs an escaping ray
    // against, so the directions must follow it. Under it z = cos theta and
    // the azimuth are independent and uniform: 32 x 32 equal-area bins.
    const std::string options = sampler_options();
    INFO(options);
    cl::Kernel kernel(program(kSamplingSource, "sampling_test.cl", options), "sphere_samples");
    set_args(kernel, cl_uint(7), kSamples);
    std::vector<cl_float4> samples = run_samples(kernel);
    const std::size_t bins = 32;
    std::vector<std::size_t> histogram(bins * bins);
    std::size_t bad_length = 0;
    Moment z;
    for (const cl_float4& s : samples) {
        D3 d = from_float4(s);
        bad_length += std::fabs(length(d) - 1.0) > 1e-6;
        z.add(d.z);
        double phi = std::atan2(d.y, d.x) + M_PI;
        auto z_bin = std::min<std::size_t>(bins - 1, std::size_t((d.z + 1.0) * 0.5 * bins));
        auto phi_bin = std::min<std::size_t>(bins - 1, std::size_t(phi / (2 * M_PI) * bins));
        ++histogram[z_bin * bins + phi_bin];
    }
    CHECK(bad_length == 0);
    check_mean("E[z]", z, 0.0);
    double statistic = chi_square(histogram, samples.size());
    INFO("chi-square " << statistic << " over " << histogram.size() << " bins");
    CHECK(statistic < chi_square_limit(histogram.size() - 1));
}

TEST_CASE("wp_sample_cosine_hemisphere has the moments of the cosine distribution",
          "[cl][sampling][statistical]") {
    const D3 normals[] = {
        {0, 0, 1},
        {0, 0, -1},
        {1, 0, 0},
        {0, -1, 0},
        normalize(D3(1, 2, -3)),
        normalize(D3(-0.3, 0.2, 0.93)),
        normalize(D3(1e-3, 0, -1)),
    };
    const std::string options = sampler_options();
    INFO(options);
    cl::Kernel kernel(program(kSamplingSource, "sampling_test.cl", options), "cosine_samples");
    cl_uint seed = 5;
    for (const D3& requested : normals) {
        cl_float4 n_float = to_float4(requested);
        D3 n = from_float4(n_float); // the normal exactly as the kernel gets it
        INFO("normal " << n.x << ", " << n.y << ", " << n.z);
        set_args(kernel, n_float, seed++, kSamples);
        std::vector<cl_float4> samples = run_samples(kernel);

        // Any orthonormal basis around n, to measure the azimuth.
        D3 helper = std::fabs(n.x) < 0.5 ? D3(1, 0, 0) : D3(0, 1, 0);
        D3 t = normalize(cross(helper, n)), b = cross(n, t);

        Moment cosine, cosine_squared;
        std::array<Moment, 3> component;
        const std::size_t bins = 16;
        std::vector<std::size_t> histogram(bins * bins);
        std::size_t bad_length = 0, below = 0;
        for (const cl_float4& s : samples) {
            D3 d = from_float4(s);
            double c = dot(d, n);
            cosine.add(c);
            cosine_squared.add(c * c);
            for (int k = 0; k < 3; ++k)
                component[k].add(d[k]);
            bad_length += std::fabs(length(d) - 1.0) > 1e-6;
            below += !(c > 0.0);
            // Under pdf cos/pi, cos^2 and the azimuth are independent and uniform.
            double phi = std::atan2(dot(d, b), dot(d, t)) + M_PI;
            auto cos_bin = std::min<std::size_t>(bins - 1, std::size_t(c * c * bins));
            auto phi_bin = std::min<std::size_t>(bins - 1, std::size_t(phi / (2 * M_PI) * bins));
            ++histogram[cos_bin * bins + phi_bin];
        }
        CHECK(bad_length == 0);
        CHECK(below == 0);
        check_mean("E[cos]", cosine, 2.0 / 3.0);
        check_mean("E[cos^2]", cosine_squared, 0.5);
        check_mean("E[d.x]", component[0], 2.0 / 3.0 * n.x);
        check_mean("E[d.y]", component[1], 2.0 / 3.0 * n.y);
        check_mean("E[d.z]", component[2], 2.0 / 3.0 * n.z);
        // Var[cos] = E[cos^2] - E[cos]^2 = 1/2 - 4/9 = 1/18.
        CHECK(std::fabs(cosine.variance() - 1.0 / 18.0) < 0.01 / 18.0);
        double statistic = chi_square(histogram, samples.size());
        INFO("chi-square " << statistic << " over " << histogram.size() << " bins");
        CHECK(statistic < chi_square_limit(histogram.size() - 1));
    }
}

TEST_CASE("wp_sincos_2pi is within 1.2e-7 of double sin and cos of 2 pi u", "[cl][sampling]") {
    cl::Kernel kernel(program(kSamplingSource, "sampling_test.cl"), "sincos_2pi");
    // Every 7th of the 2^24 numbers wp_to_unit_float makes, the quarter turns,
    // and the ends.
    const cl_uint quarter = 1u << 22;
    std::vector<cl_uint> ks = {quarter, 2 * quarter, 3 * quarter, 1u, 16777215u};
    for (cl_uint k = 0; k < (1u << 24); k += 7)
        ks.push_back(k);
    const auto count = static_cast<cl_uint>(ks.size());
    cl::Buffer in = upload(ks);
    cl::Buffer out = upload(std::vector<cl_float2>(count));
    set_args(kernel, count, in, out);
    launch(kernel, count);
    std::vector<cl_float2> got = download<cl_float2>(out, count);
    double worst = 0.0, worst_u = 0.0;
    std::size_t outside = 0; // a sine or cosine outside [-1, 1]
    for (cl_uint i = 0; i < count; ++i) {
        const double u = double(ks[i]) / 16777216.0;
        const double error = std::max(std::fabs(double(got[i].s[0]) - std::sin(2.0 * M_PI * u)),
                                      std::fabs(double(got[i].s[1]) - std::cos(2.0 * M_PI * u)));
        if (error > worst)
            worst = error, worst_u = u;
        outside += std::fabs(got[i].s[0]) > 1.0f || std::fabs(got[i].s[1]) > 1.0f;
    }
    INFO("worst error " << worst << " at u = " << worst_u);
    CHECK(worst <= 1.2e-7);
    CHECK(outside == 0);
    // The quarter turns exactly: (0, 1) at u = 1/4, (-1, 0) at 1/2, (0, -1) at 3/4.
    CHECK(got[0].s[0] == 1.0f);
    CHECK(got[0].s[1] == 0.0f);
    CHECK(got[1].s[0] == 0.0f);
    CHECK(got[1].s[1] == -1.0f);
    CHECK(got[2].s[0] == -1.0f);
    CHECK(got[2].s[1] == 0.0f);
}

TEST_CASE("wp_atan2 is within 3.5 ulps of double atan2, and atan2 at the axes and signed zeros",
          "[cl][sampling]") {
    // Directions all round the circle at every scale of |y| / |x| (the
    // reduction's three ranges and their borders), and the special points.
    std::vector<cl_float2> yx;
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> angle(-M_PI, M_PI), scale(-30.0, 30.0);
    for (int n = 0; n < 200000; ++n) {
        const double a = angle(rng), r = std::exp(scale(rng));
        yx.push_back({{static_cast<float>(r * std::sin(a)), static_cast<float>(r * std::cos(a))}});
    }
    for (float t : {0.41421354f, 0.41421357f, 0.4142136f, 2.4142134f, 2.4142137f, 1.0f})
        for (float sy : {1.0f, -1.0f})
            for (float sx : {1.0f, -1.0f})
                yx.push_back({{sy * t, sx}});
    const float zero = 0.0f, inf = std::numeric_limits<float>::infinity();
    const std::vector<cl_float2> special = {{{zero, zero}},   {{-zero, zero}}, {{zero, -zero}},
                                            {{-zero, -zero}}, {{1.0f, zero}},  {{-1.0f, zero}},
                                            {{zero, 1.0f}},   {{zero, -1.0f}}, {{-zero, -1.0f}},
                                            {{1.0f, inf}},    {{1.0f, -inf}},  {{inf, 1.0f}}};
    yx.insert(yx.end(), special.begin(), special.end());
    const auto count = static_cast<cl_uint>(yx.size());
    cl::Kernel kernel(program(kSamplingSource, "sampling_test.cl"), "atan2_of");
    cl::Buffer in = upload(yx), out = upload(std::vector<float>(count));
    set_args(kernel, count, in, out);
    launch(kernel, count);
    const std::vector<float> got = download<float>(out, count);
    double worst = 0.0;
    std::size_t worst_index = 0;
    for (cl_uint i = 0; i < count; ++i) {
        const double expected = std::atan2(double(yx[i].s[0]), double(yx[i].s[1]));
        const float rounded = static_cast<float>(expected);
        const double ulp =
            std::max(double(std::nextafter(std::fabs(rounded), 4.0f)) - std::fabs(rounded),
                     double(std::numeric_limits<float>::denorm_min()));
        const double ulps = std::fabs(got[i] - expected) / ulp;
        if (ulps > worst)
            worst = ulps, worst_index = i;
    }
    INFO("worst " << worst << " ulps at (" << yx[worst_index].s[0] << ", " << yx[worst_index].s[1]
                  << "): " << got[worst_index]);
    CHECK(worst <= 3.5);
    // The signed zeros and axes exactly as atan2 (the special points, in order).
    const std::size_t first = yx.size() - special.size();
    for (std::size_t k = 0; k < special.size(); ++k) {
        const float expected = std::atan2(special[k].s[0], special[k].s[1]);
        INFO("atan2(" << special[k].s[0] << ", " << special[k].s[1] << ")");
        CHECK(got[first + k] == expected);
        CHECK(std::signbit(got[first + k]) == std::signbit(expected));
    }
}

TEST_CASE("wp_sample_triangle gives uniform points inside the triangle",
          "[cl][sampling][statistical]") {
    const std::array<D3, 3> triangles[] = {
        {D3(0, 0, 0), D3(1, 0, 0), D3(0, 1, 0)},
        {D3(1, 2, 3), D3(-1, 0.5, 2), D3(0.3, -1, -0.5)},
        {D3(-2, 1, 0.5), D3(2.5, 1.2, -0.25), D3(0.1, -0.7, 1.9)},
    };
    const std::string options = sampler_options();
    INFO(options);
    cl::Kernel kernel(program(kSamplingSource, "sampling_test.cl", options), "triangle_samples");
    cl_uint seed = 77;
    for (const std::array<D3, 3>& requested : triangles) {
        std::array<cl_float4, 3> p_float{to_float4(requested[0]), to_float4(requested[1]),
                                         to_float4(requested[2])};
        D3 p0 = from_float4(p_float[0]), p1 = from_float4(p_float[1]), p2 = from_float4(p_float[2]);
        INFO("triangle " << p0.x << ", " << p0.y << ", " << p0.z << " ...");
        set_args(kernel, p_float[0], p_float[1], p_float[2], seed++, kSamples);
        std::vector<cl_float4> samples = run_samples(kernel);

        // Barycentrics (of p0, p1, p2) from the normal equations of p - p0 = b1 e1 + b2 e2.
        D3 e1 = p1 - p0, e2 = p2 - p0, normal = normalize(cross(e1, e2));
        double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
        double det = g11 * g22 - g12 * g12;
        const double scale = std::max({max_abs(p0), max_abs(p1), max_abs(p2)});

        std::array<Moment, 3> position, barycentric, barycentric_squared;
        const std::size_t k = 8; // 8 x 8 congruent sub-triangles: k^2 equally likely cells
        std::vector<std::size_t> cells(k * k);
        std::size_t outside = 0, off_plane = 0;
        for (const cl_float4& s : samples) {
            D3 p = from_float4(s);
            D3 r = p - p0;
            double r1 = dot(r, e1), r2 = dot(r, e2);
            double b1 = (g22 * r1 - g12 * r2) / det, b2 = (g11 * r2 - g12 * r1) / det;
            double b0 = 1.0 - b1 - b2;
            outside += b0 < -1e-6 || b1 < -1e-6 || b2 < -1e-6;
            off_plane += std::fabs(dot(r, normal)) > 1e-6 * scale;
            const double bs[3] = {b0, b1, b2};
            for (int i = 0; i < 3; ++i) {
                position[i].add(p[i]);
                barycentric[i].add(bs[i]);
                barycentric_squared[i].add(bs[i] * bs[i]);
            }
            double x = std::clamp(b1, 0.0, 1.0) * double(k),
                   y = std::clamp(b2, 0.0, 1.0) * double(k);
            std::size_t i = std::min<std::size_t>(k - 1, std::size_t(x));
            std::size_t j = std::min<std::size_t>(k - 1 - i, std::size_t(y));
            bool upper = (x - double(i)) + (y - double(j)) > 1.0 && i + j + 1 < k;
            // Cells numbered row by row: the "lower" triangle of (i, j), then its "upper" one.
            std::size_t index = 0;
            for (std::size_t row = 0; row < i; ++row)
                index += 2 * (k - row) - 1;
            index += 2 * j + (upper ? 1 : 0);
            ++cells[index];
        }
        CHECK(outside == 0);
        CHECK(off_plane == 0);
        D3 centroid = (p0 + p1 + p2) / 3.0;
        check_mean("mean x", position[0], centroid.x);
        check_mean("mean y", position[1], centroid.y);
        check_mean("mean z", position[2], centroid.z);
        for (int i = 0; i < 3; ++i) {
            check_mean("E[b]", barycentric[i], 1.0 / 3.0);
            check_mean("E[b^2]", barycentric_squared[i], 1.0 / 6.0);
        }
        double statistic = chi_square(cells, samples.size());
        INFO("chi-square " << statistic << " over " << cells.size() << " cells");
        CHECK(statistic < chi_square_limit(cells.size() - 1));
    }
}

// The dimensions of one bounce differ only in the low bits of the counter. With
// a single final round of lowbias32 the pair (BSDF_U, BSDF_V) that picks each
// diffuse bounce direction had a systematically non-uniform joint histogram:
// over 16 seeds x 2^20 pixels the chi-square on 16 x 16 bins was about 900
// against 255 +- 23 for independent uniforms. rng.h now mixes twice.
TEST_CASE("wp_random: the two BSDF dimensions of a bounce are independent",
          "[cl][rng][statistical]") {
    const std::size_t bins = 16;
    std::vector<std::size_t> histogram(bins * bins);
    const cl_uint seeds = 16;
    for (cl_uint seed = 0; seed < seeds; ++seed) {
        for (cl_uint pixel = 0; pixel < kSamples; ++pixel) {
            float u1 = wp_random(seed, pixel, 0u, 0u, WP_DIM_BSDF_U);
            float u2 = wp_random(seed, pixel, 0u, 0u, WP_DIM_BSDF_V);
            ++histogram[std::size_t(u1 * float(bins)) * bins + std::size_t(u2 * float(bins))];
        }
    }
    double statistic = chi_square(histogram, std::size_t(seeds) * kSamples);
    INFO("chi-square " << statistic << " over " << histogram.size() << " bins");
    CHECK(statistic < chi_square_limit(histogram.size() - 1));
}

// wp_pick_light for each u (lights.h).
const char* const kPickLightsSource = R"CL(
#include "lights.h"
__kernel void pick_lights(__global const WpLight* lights, uint light_count, uint count,
                          __global const float* u, __global uint* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    out[i] = wp_pick_light(lights, light_count, u[i]);
}
)CL";

// lights.h picks the light for next-event estimation by searching the light
// table's cumulative area fractions: the first light whose cdf exceeds u, so
// each light is picked for an interval of u as long as its share of the area.
TEST_CASE("wp_pick_light returns the first light whose cdf exceeds u", "[cl][sampling]") {
    // Areas 1, 0 (a degenerate light, never to be picked), 2.5, 0.5 and 4.
    const double areas[] = {1.0, 0.0, 2.5, 0.5, 4.0};
    const double total = 8.0;
    wp::DeviceArray<WpLight> lights;
    double running = 0.0;
    for (std::size_t i = 0; i < std::size(areas); ++i) {
        running += areas[i];
        WpLight light{};
        light.triangle = cl_uint(10 + i);
        light.cdf = float(running / total);
        lights.push_back(light);
    }
    REQUIRE(lights.back().cdf == 1.0f);
    wp::set_light_guides(lights); // as flatten_scene does (0 would do as well, only slower)

    // Every boundary, the floats on either side of it, and random u in [0, 1).
    std::vector<cl_float> us = {0.0f, std::nextafter(1.0f, 0.0f)};
    for (const WpLight& light : lights)
        for (float u :
             {std::nextafter(light.cdf, 0.0f), light.cdf, std::nextafter(light.cdf, 2.0f)})
            if (u < 1.0f)
                us.push_back(u);
    for (cl_uint i = 0; i < 4000; ++i)
        us.push_back(wp_random(31u, i, 0u, 0u, WP_DIM_LIGHT_PICK));

    // With the count compiled in (small scenes) the search takes a fixed
    // number of select steps; it must find the same light. Counts 2 to 4 use
    // a prefix of the table (the last cdf below 1: u past it takes the last).
    for (cl_uint light_count : {5u, 1u, 2u, 3u, 4u})
        for (bool fixed : {false, true}) {
            INFO(light_count << " lights" << (fixed ? ", WP_LIGHT_COUNT compiled in" : ""));
            const std::string options =
                fixed ? "-D WP_LIGHT_COUNT=" + std::to_string(light_count) : "";
            cl::Kernel kernel(program(kPickLightsSource, "pick_light_test.cl", options),
                              "pick_lights");
            cl::Buffer light_buffer = upload(lights), u_buffer = upload(us);
            cl::Buffer out = upload(std::vector<cl_uint>(us.size(), 0xffffffffu));
            set_args(kernel, light_buffer, light_count, cl_uint(us.size()), u_buffer, out);
            launch(kernel, us.size());
            std::vector<cl_uint> got = download<cl_uint>(out, us.size());
            std::vector<std::size_t> picked(std::size(areas));
            for (std::size_t i = 0; i < us.size(); ++i) {
                cl_uint expected = light_count - 1;
                for (cl_uint l = 0; l + 1 < light_count; ++l) {
                    if (double(lights[l].cdf) > double(us[i])) {
                        expected = l;
                        break;
                    }
                }
                INFO("u = " << us[i]);
                CHECK(got[i] == expected);
                if (got[i] < picked.size())
                    ++picked[got[i]];
            }
            if (light_count > 2) // with two, the zero-area light is the prefix's last
                CHECK(picked[1] == 0);
            if (light_count == 1)
                CHECK(picked[0] == us.size());
        }
}

// Many lights of very unequal areas (a few large ones, runs of tiny and of
// zero-area ones): the guided search (WpLight.guide) finds exactly the light
// the binary search finds, at every cdf, on both sides of it, at the bins'
// edges k / count and at random u.
TEST_CASE("wp_pick_light's guided search finds the binary search's light among 10^4",
          "[cl][sampling]") {
    const std::size_t n = 10007;
    std::vector<double> areas(n);
    for (std::size_t i = 0; i < n; ++i)
        areas[i] = i % 997 == 0 ? 500.0 : (i % 13 == 0 ? 0.0 : (i % 7 == 0 ? 1e-6 : 1.0));
    double total = 0.0;
    for (double a : areas)
        total += a;
    wp::DeviceArray<WpLight> lights(n);
    double running = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        running += areas[i];
        lights[i].triangle = cl_uint(i);
        lights[i].cdf = float(running / total);
    }
    lights.back().cdf = 1.0f;
    wp::set_light_guides(lights);
    std::vector<cl_float> us;
    for (const WpLight& light : lights)
        for (float u : {std::nextafter(light.cdf, 0.0f), light.cdf})
            if (u < 1.0f)
                us.push_back(u);
    for (std::size_t k = 0; k < n; ++k) {
        const float edge = float(double(k) / double(n));
        us.push_back(edge);
        us.push_back(std::nextafter(edge, 0.0f));
    }
    for (cl_uint i = 0; i < 20000; ++i)
        us.push_back(wp_random(5u, i, 0u, 0u, WP_DIM_LIGHT_PICK));
    for (float& u : us)
        u = std::max(0.0f, u);
    cl::Kernel kernel(program(kPickLightsSource, "pick_light_test.cl"), "pick_lights");
    cl::Buffer light_buffer = upload(lights), u_buffer = upload(us);
    cl::Buffer out = upload(std::vector<cl_uint>(us.size(), 0xffffffffu));
    set_args(kernel, light_buffer, cl_uint(n), cl_uint(us.size()), u_buffer, out);
    launch(kernel, us.size());
    const std::vector<cl_uint> got = download<cl_uint>(out, us.size());
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < us.size(); ++i) {
        // The binary search of the kernels before guides, on the host.
        std::size_t low = 0, high = n - 1;
        while (low < high) {
            const std::size_t mid = (low + high) / 2;
            if (lights[mid].cdf > us[i])
                high = mid;
            else
                low = mid + 1;
        }
        wrong += got[i] != low;
    }
    INFO(wrong << " of " << us.size() << " picks differ");
    CHECK(wrong == 0);
}
