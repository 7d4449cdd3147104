// The Owen-scrambled Sobol sampler (kernels/sobol.h): the device's numbers are
// the host's, the Sobol points are the textbook ones, every power-of-two block
// of a pixel's samples is a (0, m, 2)-net, the jitter pairs have a small
// L2-star discrepancy (against a bound derived below), and the pairs, bounces
// and pixels are mutually independent.
#include "rng.h"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace wp::test;

namespace {

const char* const kRandomSource = R"CL(
#include "rng.h"
__kernel void randoms(uint count, __global const uint4* keys, __global const uint* dimensions,
                      __global float* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint4 k = keys[i];
    out[i] = wp_random(k.x, k.y, k.z, k.w, dimensions[i]);
}
)CL";

const char* const kBounceSource = R"CL(
#include "rng.h"
__kernel void bounce_randoms(uint count, __global const uint4* keys, __global float* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    uint4 k = keys[i];
    float4 first, second;
    wp_random_bounce_pairs(k.x, k.y, k.z, k.w, &first, &second);
    float numbers[WP_DIMS_PER_BOUNCE];
    wp_bounce_numbers(first, second, numbers);
    for (uint d = 0u; d < WP_DIMS_PER_BOUNCE; ++d)
        out[i * WP_DIMS_PER_BOUNCE + d] = numbers[d];
}
)CL";

// Keys (seed, pixel, sample, bounce) and dimensions: small and huge values.
struct Keys {
    std::vector<cl_uint4> keys;
    std::vector<cl_uint> dimensions;
};

Keys test_keys() {
    Keys k;
    std::uint32_t state = 12345u;
    auto next = [&state] { return state = wp_mix32(state + 0x9e3779b9u); };
    for (cl_uint i = 0; i < 4096; ++i) {
        cl_uint4 key;
        key.s[0] = i % 3u == 0u ? i : next();
        key.s[1] = i % 5u == 0u ? i / 5u : next();
        key.s[2] = i % 2u == 0u ? i / 2u : next();
        key.s[3] = next() % 64u;
        k.keys.push_back(key);
        k.dimensions.push_back(i % 3u == 1u ? next() % 16u : i % WP_DIMS_PER_BOUNCE);
    }
    return k;
}

// The first 2^m samples of each pair must be a (0, m, 2)-net: every
// elementary interval [a / 2^j, (a+1) / 2^j) x [b / 2^(m-j), (b+1) / 2^(m-j))
// holds exactly one point. Returns the number of intervals that do not.
int net_violations(const std::vector<float>& x, const std::vector<float>& y, int m) {
    const std::size_t n = std::size_t(1) << m;
    int violations = 0;
    for (int j = 0; j <= m; ++j) {
        std::vector<int> count(n, 0);
        for (std::size_t i = 0; i < n; ++i) {
            auto a = std::size_t(double(x[i]) * double(1u << j));
            auto b = std::size_t(double(y[i]) * double(1u << (m - j)));
            ++count[(a << (m - j)) | b];
        }
        violations += int(std::count_if(count.begin(), count.end(), [](int c) { return c != 1; }));
    }
    return violations;
}

// The squared L2-star discrepancy of points in [0, 1)^2 (Warnock's formula):
// the integral over anchors t of (fraction of points in [0, t) - area of [0, t))^2.
double l2_star_discrepancy_squared(const std::vector<float>& x, const std::vector<float>& y) {
    const std::size_t n = x.size();
    double single = 0.0, both = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        single += (1.0 - double(x[i]) * x[i]) * (1.0 - double(y[i]) * y[i]);
        for (std::size_t k = 0; k < n; ++k)
            both += (1.0 - std::max<double>(x[i], x[k])) * (1.0 - std::max<double>(y[i], y[k]));
    }
    return 1.0 / 9.0 - single / (2.0 * double(n)) + both / (double(n) * double(n));
}

// Pearson's correlation coefficient and chi-square helpers.
struct Correlation {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, n = 0;
    void add(double x, double y) {
        sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y, n += 1;
    }
    double r() const {
        double cov = sxy / n - sx / n * sy / n;
        return cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
    }
};

double chi_square_limit(double dof) {
    return dof + 5.0 * std::sqrt(2.0 * dof);
}

std::uint32_t reverse_bits_naive(std::uint32_t x) {
    std::uint32_t r = 0;
    for (int b = 0; b < 32; ++b)
        r |= ((x >> b) & 1u) << (31 - b);
    return r;
}

} // namespace

TEST_CASE("sobol: the device's numbers are the host's, bit for bit", "[cl][rng][sobol]") {
    const Keys k = test_keys();
    const auto count = cl_uint(k.keys.size());
    for (int sampler : {WP_SAMPLER_INDEPENDENT, WP_SAMPLER_SOBOL}) {
        INFO("WP_SAMPLER=" << sampler);
        cl::Kernel kernel(
            program(kRandomSource, "sobol_test.cl", "-D WP_SAMPLER=" + std::to_string(sampler)),
            "randoms");
        cl::Buffer keys = upload(k.keys), dimensions = upload(k.dimensions);
        cl::Buffer out = upload(std::vector<cl_float>(count, -1.0f));
        set_args(kernel, count, keys, dimensions, out);
        launch(kernel, count);
        const std::vector<cl_float> device = download<cl_float>(out, count);
        int differ = 0;
        for (cl_uint i = 0; i < count; ++i) {
            const cl_uint4& key = k.keys[i];
            float host =
                sampler == WP_SAMPLER_SOBOL
                    ? wp_sobol_random(key.s[0], key.s[1], key.s[2], key.s[3], k.dimensions[i])
                    : wp_independent_random(key.s[0], key.s[1], key.s[2], key.s[3],
                                            k.dimensions[i]);
            differ += device[i] != host;
            CHECK((device[i] >= 0.0f && device[i] < 1.0f));
            // Exact: a multiple of 2^-24.
            CHECK(std::ldexp(double(device[i]), 24) ==
                  std::floor(std::ldexp(double(device[i]), 24)));
        }
        CHECK(differ == 0);
    }
}

TEST_CASE("sobol: the building blocks are the textbook ones", "[rng][sobol]") {
    std::uint32_t state = 99u;
    for (int i = 0; i < 20000; ++i) {
        std::uint32_t x = i < 64 ? std::uint32_t(i) : (state = wp_mix32(state + 1u));
        CHECK(wp_reverse_bits(x) == reverse_bits_naive(x));
        // The second Sobol dimension's generator matrix is Pascal's triangle
        // mod 2: output digit j (weight 2^-(j+1)) is the xor over index bits
        // k >= j with C(k, j) odd, which by Lucas' theorem is (k & j) == j.
        std::uint32_t expected = 0;
        for (int j = 0; j < 32; ++j) {
            std::uint32_t digit = 0;
            for (int b = j; b < 32; ++b)
                if ((b & j) == j)
                    digit ^= (x >> b) & 1u;
            expected |= digit << (31 - j);
        }
        CHECK(wp_sobol_second(x) == expected);
        CHECK(wp_sobol_first(x) == reverse_bits_naive(x));
    }
    // The well-known first points: (0, 0), (1/2, 1/2), (1/4, 3/4), (3/4, 1/4), (1/8, 5/8).
    const double points[][2] = {{0, 0}, {0.5, 0.5}, {0.25, 0.75}, {0.75, 0.25}, {0.125, 0.625}};
    for (std::uint32_t i = 0; i < 5; ++i) {
        CHECK(std::ldexp(double(wp_sobol_first(i)), -32) == points[i][0]);
        CHECK(std::ldexp(double(wp_sobol_second(i)), -32) == points[i][1]);
    }
    // The scramble is a bijection that keeps prefixes: values that share their
    // top k bits still share them after the scramble (a nested scramble).
    for (std::uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
        std::vector<std::uint32_t> image;
        for (std::uint32_t x = 0; x < (1u << 12); ++x)
            image.push_back(wp_nested_uniform_scramble(x << 20, seed) >> 20);
        std::sort(image.begin(), image.end());
        CHECK(std::adjacent_find(image.begin(), image.end()) == image.end());
        for (std::uint32_t x = 0; x < 1000; ++x) {
            std::uint32_t a = wp_mix32(x), b = (a & 0xffff0000u) | (wp_mix32(a) & 0xffffu);
            CHECK((wp_nested_uniform_scramble(a, seed) >> 16) ==
                  (wp_nested_uniform_scramble(b, seed) >> 16));
        }
    }
}

TEST_CASE("sobol: every power-of-two block of a pixel's samples is a (0, m, 2)-net",
          "[rng][sobol]") {
    const cl_uint pairs[][2] = {{WP_DIM_JITTER_X, WP_DIM_JITTER_Y},
                                {WP_DIM_LIGHT_PICK, WP_DIM_ROULETTE},
                                {WP_DIM_LIGHT_U, WP_DIM_LIGHT_V},
                                {WP_DIM_BSDF_U, WP_DIM_BSDF_V}};
    for (cl_uint seed : {0u, 7u, 0x12345678u}) {
        for (cl_uint pixel : {0u, 1u, 65535u, 4000000000u}) {
            for (cl_uint bounce : {0u, 1u, 9u}) {
                for (const auto& pair : pairs) {
                    for (int m : {0, 1, 4, 6, 8, 10}) {
                        for (cl_uint block : {0u, 1u, 5u}) {
                            const cl_uint n = 1u << m, first = block * n;
                            std::vector<float> x, y;
                            for (cl_uint s = first; s < first + n; ++s) {
                                x.push_back(wp_sobol_random(seed, pixel, s, bounce, pair[0]));
                                y.push_back(wp_sobol_random(seed, pixel, s, bounce, pair[1]));
                            }
                            INFO("seed " << seed << " pixel " << pixel << " bounce " << bounce
                                         << " dimensions " << pair[0] << "," << pair[1] << " m "
                                         << m << " block " << block);
                            CHECK(net_violations(x, y, m) == 0);
                        }
                    }
                }
            }
        }
    }
}

// Independent uniform points: for each anchor t, N F_N(t) is binomial
// (N, |[0, t)|), so E[(F_N - |[0,t)|)^2] = |[0,t)| (1 - |[0,t)|) / N and
//   E[T^2] = (1/N) integral (t1 t2 - t1^2 t2^2) dt = (1/4 - 1/9) / N = 5 / (36 N).
// An Owen-scrambled (0, m, 2)-net, N = 2^m: write the anchor's t1 in binary,
// t1 = sum_k d_k 2^-k. [0, t) splits into one strip [c_k, c_k + 2^-k) x
// [0, t2) for each digit d_k = 1, k <= m, and a remainder of width below
// 2^-m. A strip's elementary column holds 2^(m-k) points, one in each row of
// height 2^-(m-k); all rows below t2 are whole but one, whose point lies
// uniformly in its cell under the scramble: the strip's count error has mean
// 0 and variance r (1 - r) <= 1/4 (r the cut row's fraction). The remainder's
// column holds one point, uniform in the column: error variance <= 1/4 too.
// So N (F_N - |[0,t)|) is a sum of at most D(t1) + 1 terms of standard
// deviation <= 1/2, D the number of ones among t1's first m digits, and (by
// Minkowski's inequality, whatever their correlation) has mean square at most
// (D + 1)^2 / 4. D is binomial (m, 1/2) for uniform t1: E[(D+1)^2] = m/4 +
// (m/2 + 1)^2. Hence E[T^2] <= (m/4 + (m/2 + 1)^2) / (4 N^2): at N = 64 about
// half, at N = 256 a fifth of the independent expectation.
TEST_CASE("sobol: a pixel's jitter points have a small L2-star discrepancy",
          "[cl][rng][sobol][statistical]") {
    const cl_uint pixels = 512;
    for (int m : {6, 8}) {
        const cl_uint n = 1u << m;
        const double independent_expected = 5.0 / (36.0 * n);
        const double net_bound = (m / 4.0 + (m / 2.0 + 1) * (m / 2.0 + 1)) / (4.0 * n * n);
        for (int sampler : {WP_SAMPLER_INDEPENDENT, WP_SAMPLER_SOBOL}) {
            double sum = 0.0, sum_squares = 0.0;
            for (cl_uint pixel = 0; pixel < pixels; ++pixel) {
                std::vector<float> x, y;
                for (cl_uint s = 0; s < n; ++s) {
                    auto random =
                        sampler == WP_SAMPLER_SOBOL ? wp_sobol_random : wp_independent_random;
                    x.push_back(random(3u, pixel, s, 0u, WP_DIM_JITTER_X));
                    y.push_back(random(3u, pixel, s, 0u, WP_DIM_JITTER_Y));
                }
                double t2 = l2_star_discrepancy_squared(x, y);
                sum += t2;
                sum_squares += t2 * t2;
            }
            const double mean = sum / pixels;
            const double error =
                std::sqrt((sum_squares / pixels - mean * mean) / double(pixels - 1));
            INFO("N " << n << " sampler " << sampler << ": mean T^2 " << mean << " +- " << error
                      << "; independent expectation " << independent_expected << ", net bound "
                      << net_bound);
            if (sampler == WP_SAMPLER_INDEPENDENT) {
                // The formula (and this code) checked on the independent sampler.
                CHECK(std::fabs(mean - independent_expected) < 5.0 * error);
            } else {
                CHECK(net_bound < 0.5 * independent_expected);
                CHECK(mean + 5.0 * error < net_bound);
            }
        }
    }
}

// Independence, where the sampler must not stratify: two pairs of one sample,
// one pair at two bounces, one pair at two neighbouring pixels. Pooled over
// pixels and samples, the correlation of independent uniforms has standard
// error 1/sqrt(n). Within one pixel's 256 samples, a 16 x 16 histogram of
// independent uniforms has a chi-square of mean 255 (summed over pixels: 255
// per pixel); that is the upper limit. Without the per-pair index shuffle,
// jitter x and light u (both van der Corput, differently scrambled) would fill
// only 16 of the 256 cells, a chi-square of 3840 per pixel.
// The shuffle is a nested permutation, so its pairing is not a uniformly
// random one: the 16 samples that share the top 4 bits of the index put one
// point in each row and each column (each coordinate is stratified on its
// own), so the histogram is a sum of 16 random 16 x 16 permutation matrices,
// a cell count of variance 16 (1/16) (15/16) and a chi-square of mean 240 per
// pixel; below 255, as a count with stratified margins should be. The lower
// limit catches the other failure, two pairs stratified against each other
// (a net puts one point in each cell: a chi-square of 0).
TEST_CASE("sobol and independent: pairs, bounces and pixels are independent of each other",
          "[rng][sobol][statistical]") {
    struct Coordinate {
        cl_uint pixel_offset, bounce, dimension;
    };
    struct Case {
        const char* what;
        Coordinate a, b;
    };
    const Case cases[] = {
        {"jitter x / light u", {0, 0, WP_DIM_JITTER_X}, {0, 0, WP_DIM_LIGHT_U}},
        {"jitter y / bsdf v", {0, 0, WP_DIM_JITTER_Y}, {0, 0, WP_DIM_BSDF_V}},
        {"light pick / light u", {0, 1, WP_DIM_LIGHT_PICK}, {0, 1, WP_DIM_LIGHT_U}},
        {"roulette / bsdf u", {0, 2, WP_DIM_ROULETTE}, {0, 2, WP_DIM_BSDF_U}},
        {"bsdf u at bounces 0 and 1", {0, 0, WP_DIM_BSDF_U}, {0, 1, WP_DIM_BSDF_U}},
        {"light v at bounces 3 and 4", {0, 3, WP_DIM_LIGHT_V}, {0, 4, WP_DIM_LIGHT_V}},
        {"jitter x at neighbouring pixels", {0, 0, WP_DIM_JITTER_X}, {1, 0, WP_DIM_JITTER_X}},
        {"bsdf u at neighbouring pixels", {0, 1, WP_DIM_BSDF_U}, {1, 1, WP_DIM_BSDF_U}},
        // The lobe number, past a bounce's eight: a pair of its own (Sobol), a
        // counter of its own (independent), never the next bounce's first
        // number (the thin lens reads bounce 1's jitter pair).
        {"bsdf lobe / bsdf u", {0, 1, WP_DIM_BSDF_LOBE}, {0, 1, WP_DIM_BSDF_U}},
        {"bsdf lobe / bsdf v", {0, 1, WP_DIM_BSDF_LOBE}, {0, 1, WP_DIM_BSDF_V}},
        {"bsdf lobe at bounce 0 / lens u", {0, 0, WP_DIM_BSDF_LOBE}, {0, 1, WP_DIM_LENS_U}},
        {"bsdf lobe at bounces 2 and 3", {0, 2, WP_DIM_BSDF_LOBE}, {0, 3, WP_DIM_BSDF_LOBE}},
    };
    const cl_uint pixels = 2048, samples = 256, bins = 16;
    for (int sampler : {WP_SAMPLER_SOBOL, WP_SAMPLER_INDEPENDENT})
        for (const Case& c : cases) {
            INFO("WP_SAMPLER=" << sampler << ": " << c.what);
            auto random = [sampler](cl_uint pixel, cl_uint sample, const Coordinate& at) {
                return sampler == WP_SAMPLER_SOBOL
                           ? wp_sobol_random(11u, pixel, sample, at.bounce, at.dimension)
                           : wp_independent_random(11u, pixel, sample, at.bounce, at.dimension);
            };
            Correlation correlation;
            double chi_square = 0.0;
            for (cl_uint p = 0; p < pixels; ++p) {
                std::vector<double> histogram(bins * bins, 0.0);
                for (cl_uint s = 0; s < samples; ++s) {
                    double u = random(2 * p + c.a.pixel_offset, s, c.a);
                    double v = random(2 * p + c.b.pixel_offset, s, c.b);
                    correlation.add(u, v);
                    histogram[std::size_t(u * bins) * bins + std::size_t(v * bins)] += 1.0;
                }
                const double expected = double(samples) / double(bins * bins);
                for (double h : histogram)
                    chi_square += (h - expected) * (h - expected) / expected;
            }
            const double n = double(pixels) * samples;
            INFO("correlation " << correlation.r() << ", chi-square " << chi_square << " over "
                                << pixels << " x 255 degrees of freedom");
            CHECK(std::fabs(correlation.r()) < 5.0 / std::sqrt(n));
            CHECK(chi_square < chi_square_limit(double(pixels) * 255.0));
            CHECK(chi_square > double(pixels) * 240.0 - 5.0 * std::sqrt(2.0 * pixels * 255.0));
        }
}

TEST_CASE("sobol: a bounce's eight numbers drawn at once are wp_random's, bit for bit",
          "[cl][rng][sobol]") {
    const Keys k = test_keys();
    const auto count = cl_uint(k.keys.size());
    // The last build is the Sobol sampler with Oclgrind's table reversal.
    const std::vector<std::pair<int, std::string>> builds = {
        {WP_SAMPLER_INDEPENDENT, ""},
        {WP_SAMPLER_SOBOL, ""},
        {WP_SAMPLER_SOBOL, " -D WP_BIT_REVERSAL_TABLE=1"}};
    for (const auto& [sampler, extra] : builds) {
        INFO("WP_SAMPLER=" << sampler << extra);
        cl::Kernel kernel(program(kBounceSource, "sobol_bounce_test.cl",
                                  "-D WP_SAMPLER=" + std::to_string(sampler) + extra),
                          "bounce_randoms");
        cl::Buffer keys = upload(k.keys);
        cl::Buffer out = upload(std::vector<cl_float>(count * WP_DIMS_PER_BOUNCE, -1.0f));
        set_args(kernel, count, keys, out);
        launch(kernel, count);
        const std::vector<cl_float> device = download<cl_float>(out, count * WP_DIMS_PER_BOUNCE);
        int differ = 0;
        for (cl_uint i = 0; i < count; ++i) {
            const cl_uint4& key = k.keys[i];
            for (cl_uint d = 0; d < WP_DIMS_PER_BOUNCE; ++d) {
                const float host =
                    sampler == WP_SAMPLER_SOBOL
                        ? wp_sobol_random(key.s[0], key.s[1], key.s[2], key.s[3], d)
                        : wp_independent_random(key.s[0], key.s[1], key.s[2], key.s[3], d);
                differ += device[i * WP_DIMS_PER_BOUNCE + d] != host;
            }
        }
        CHECK(differ == 0);
    }
}
