// The camera's sampling routines on the device (kernels/camera.h,
// kernels/sampling.h): the thin lens's concentric disk map and the tent and
// Gaussian pixel filters, whole and restricted to the image at its edge,
// each by a chi-square test of 2^20 samples against its density, integrated
// over each bin in double precision on the host.
#include "rng.h"
#include "support/chi_square.hpp"
#include "support/kernel_test_util.hpp"

#include <cmath>
#include <vector>

using namespace wp::test;

namespace {

const char* const kCameraSource = R"CL(
#include "camera.h"
#include "rng.h"

__kernel void disk_samples(uint seed, uint count, __global float2* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float u1 = wp_random(seed, i, 0u, WP_LENS_BOUNCE, WP_DIM_LENS_U);
    float u2 = wp_random(seed, i, 0u, WP_LENS_BOUNCE, WP_DIM_LENS_V);
    out[i] = wp_sample_concentric_disk(u1, u2);
}

/* Offsets from the pixel's centre: kind 1 tent, 2 Gaussian (WP_FILTER_*). */
__kernel void filter_samples(uint kind, float radius, float scale, float bias, uint seed,
                             uint count, __global float* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float u = wp_random(seed, i, 0u, 0u, WP_DIM_JITTER_X);
    out[i] = kind == WP_FILTER_TENT ? wp_sample_tent(u, radius)
                                    : wp_sample_gaussian_filter(u, radius, scale, bias);
}

/* Positions (pixels from the image's edge) of samples for pixel `index` of
 * `size`, as generate.cl draws them: near the edge, from the filter
 * restricted to the image. */
__kernel void filter_positions(uint kind, float radius, float scale, float bias, uint index,
                               uint size, uint seed, uint count, __global float* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    WpCamera camera; /* only the filter's fields are read */
    camera.filter = kind;
    camera.filter_radius = radius;
    camera.filter_scale = scale;
    camera.filter_bias = bias;
    float u = wp_random(seed, i, 0u, 0u, WP_DIM_JITTER_X);
    out[i] = wp_filter_position(&camera, index, size, u);
}
)CL";

constexpr cl_uint kSamples = 1u << 20;
constexpr double kPi = 3.14159265358979323846;

// The smallest p-value a test accepts: 1e-3 per test over the few tests of
// this file keeps a false alarm rare, while a wrong density gives p ~ 0.
constexpr double kSignificance = 1e-3;

// The density of a filter, as Mitsuba defines it (rfilters/tent.cpp,
// rfilters/gaussian.cpp), unnormalised.
struct Filter {
    cl_uint kind = WP_FILTER_TENT;
    double radius = 1.0; // tent
    double stddev = 0.5; // gaussian, which ends at 4 stddev

    double radius_of() const { return kind == WP_FILTER_GAUSSIAN ? 4.0 * stddev : radius; }

    double eval(double x) const {
        if (kind == WP_FILTER_TENT)
            return std::max(0.0, 1.0 - std::fabs(x) / radius);
        const double alpha = -1.0 / (2.0 * stddev * stddev), r = 4.0 * stddev;
        return std::max(0.0, std::exp(alpha * x * x) - std::exp(alpha * r * r));
    }
    // The integral of eval over [a, b], by composite Simpson's rule: the
    // reference stays the definition, not the closed forms the kernel uses.
    double integral(double a, double b) const {
        constexpr int kSteps = 64; // even
        const double h = (b - a) / kSteps;
        double sum = eval(a) + eval(b);
        for (int i = 1; i < kSteps; ++i)
            sum += (i % 2 ? 4.0 : 2.0) * eval(a + i * h);
        return sum * h / 3.0;
    }
};

std::vector<float> filter_samples(const Filter& f, cl_uint seed) {
    const double radius = f.radius_of();
    const double scale = 1.0 / (f.stddev * std::sqrt(2.0));
    cl::Kernel kernel(program(kCameraSource, "camera_test.cl"), "filter_samples");
    cl::Buffer out = upload(std::vector<float>(kSamples));
    set_args(kernel, f.kind, static_cast<float>(radius), static_cast<float>(scale),
             static_cast<float>(std::exp(-(radius * scale) * (radius * scale))), seed, kSamples,
             out);
    launch(kernel, kSamples);
    return download<float>(out, kSamples);
}

// Samples' positions for pixel `index` of an image `size` pixels wide.
std::vector<float> filter_positions(const Filter& f, cl_uint index, cl_uint size, cl_uint seed) {
    const double radius = f.radius_of();
    const double scale = 1.0 / (f.stddev * std::sqrt(2.0));
    cl::Kernel kernel(program(kCameraSource, "camera_test.cl"), "filter_positions");
    cl::Buffer out = upload(std::vector<float>(kSamples));
    set_args(kernel, f.kind, static_cast<float>(radius), static_cast<float>(scale),
             static_cast<float>(std::exp(-(radius * scale) * (radius * scale))), index, size, seed,
             kSamples, out);
    launch(kernel, kSamples);
    return download<float>(out, kSamples);
}

// Samples x against the filter's density restricted to [lo, hi] (offsets
// from the pixel's centre, centre at 0): every sample inside, a chi-square
// test in 80 bins, and the first two moments within 5 standard errors of
// the density's (a check of the tails, where the histogram's bins pool).
void check_filter_samples(const std::vector<float>& x, const Filter& f, double lo, double hi) {
    constexpr int kBins = 80;
    std::vector<double> observed(kBins, 0.0), expected(kBins);
    std::size_t outside = 0;
    double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
    for (float v : x) {
        if (!(v >= lo && v <= hi)) {
            ++outside;
            continue;
        }
        observed[std::min(kBins - 1, static_cast<int>((v - lo) / (hi - lo) * kBins))] += 1.0;
        const double v2 = double(v) * v;
        sum += v;
        sum2 += v2;
        sum4 += v2 * v2;
    }
    CHECK(outside == 0);
    const double total = f.integral(lo, hi);
    for (int i = 0; i < kBins; ++i)
        expected[i] = double(kSamples) *
                      f.integral(lo + (hi - lo) * i / kBins, lo + (hi - lo) * (i + 1) / kBins) /
                      total;
    const ChiSquare result = chi_square(observed, expected);
    INFO("chi-square " << result.statistic << " for " << result.dof << " degrees of freedom, p "
                       << result.p_value);
    CHECK(result.outside == 0);
    CHECK(result.p_value > kSignificance);

    // The density's moments by Simpson's rule.
    double m1_reference = 0.0, m2_reference = 0.0;
    constexpr int kSteps = 4096;
    const double h = (hi - lo) / kSteps;
    for (int i = 0; i <= kSteps; ++i) {
        const double t = lo + i * h;
        const double w = (i == 0 || i == kSteps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        m1_reference += w * t * f.eval(t);
        m2_reference += w * t * t * f.eval(t);
    }
    m1_reference *= h / 3.0 / total;
    m2_reference *= h / 3.0 / total;
    const double n = double(kSamples), m1 = sum / n, m2 = sum2 / n;
    const double m1_error = std::sqrt((m2 - m1 * m1) / n);
    const double m2_error = std::sqrt((sum4 / n - m2 * m2) / n);
    INFO("mean " << m1 << " +- " << m1_error << ", expected " << m1_reference << "; second moment "
                 << m2 << " +- " << m2_error << ", expected " << m2_reference);
    CHECK(std::fabs(m1 - m1_reference) <= 5.0 * m1_error);
    CHECK(std::fabs(m2 - m2_reference) <= 5.0 * m2_error);
}

} // namespace

TEST_CASE("camera: the concentric disk map is uniform on the unit disk (chi-square)",
          "[cl][camera][statistical]") {
    cl::Kernel kernel(program(kCameraSource, "camera_test.cl"), "disk_samples");
    cl::Buffer out = upload(std::vector<cl_float2>(kSamples));
    const cl_uint seed = 1234;
    set_args(kernel, seed, kSamples, out);
    launch(kernel, kSamples);
    const std::vector<cl_float2> points = download<cl_float2>(out, kSamples);

    // Bins of equal area: 16 rings of equal r^2, 32 sectors each.
    constexpr int kRings = 16, kSectors = 32;
    std::vector<double> observed(kRings * kSectors, 0.0);
    std::size_t outside = 0;
    for (const cl_float2& p : points) {
        const double x = p.s[0], y = p.s[1], r2 = x * x + y * y;
        if (r2 > 1.0 + 1e-6) {
            ++outside;
            continue;
        }
        const int ring = std::min(kRings - 1, static_cast<int>(r2 * kRings));
        const double phi = std::atan2(y, x) + kPi; // [0, 2 pi]
        const int sector = std::min(kSectors - 1, static_cast<int>(phi / (2.0 * kPi) * kSectors));
        observed[ring * kSectors + sector] += 1.0;
    }
    CHECK(outside == 0);
    const std::vector<double> expected(kRings * kSectors, double(kSamples) / (kRings * kSectors));
    const ChiSquare result = chi_square(observed, expected);
    INFO("chi-square " << result.statistic << " for " << result.dof << " degrees of freedom, p "
                       << result.p_value);
    CHECK(result.p_value > kSignificance);
}

TEST_CASE("camera: the tent and Gaussian filters' samples follow the filters (chi-square)",
          "[cl][camera][statistical]") {
    const std::vector<Filter> filters{
        {WP_FILTER_TENT, 1.0, 0.5},      // Mitsuba's default tent
        {WP_FILTER_TENT, 2.5, 0.5},      // a wider one
        {WP_FILTER_GAUSSIAN, 0.0, 0.5},  // Mitsuba's default Gaussian: radius 2
        {WP_FILTER_GAUSSIAN, 0.0, 0.25}, // a narrower one
    };
    cl_uint seed = 99; // one per filter: independent tests
    for (const Filter& f : filters) {
        const double radius = f.radius_of();
        INFO((f.kind == WP_FILTER_TENT ? "tent radius " : "gaussian stddev ")
             << (f.kind == WP_FILTER_TENT ? f.radius : f.stddev));
        check_filter_samples(filter_samples(f, seed++), f, -radius, radius);
    }
}

TEST_CASE("camera: a pixel near the image's edge samples its filter restricted to the image "
          "(chi-square)",
          "[cl][camera][statistical]") {
    // Mitsuba's film draws positions only inside the image and weights each
    // by the filter, so a pixel within the filter's radius of the edge
    // averages its footprint's part inside the image (docs/lights-and-
    // camera.md, "the film's edge"); wp_filter_position draws from that part
    // alone. The whole filter would put samples outside the image, which the
    // test counts.
    struct Case {
        Filter f;
        cl_uint index, size;
    };
    const std::vector<Case> cases{
        {{WP_FILTER_GAUSSIAN, 0.0, 0.5}, 0, 32},  // the first column: [-0.5, 2]
        {{WP_FILTER_GAUSSIAN, 0.0, 0.5}, 1, 32},  // the second: [-1.5, 2]
        {{WP_FILTER_GAUSSIAN, 0.0, 0.5}, 31, 32}, // the last: [-2, 0.5]
        {{WP_FILTER_GAUSSIAN, 0.0, 0.5}, 1, 3},   // both sides: [-1.5, 1.5]
        {{WP_FILTER_TENT, 1.0, 0.5}, 0, 32},      // [-0.5, 1]
        {{WP_FILTER_TENT, 2.5, 0.5}, 1, 2},       // [-1.5, 0.5]
    };
    cl_uint seed = 199; // one per case: independent tests
    for (const Case& c : cases) {
        const double centre = c.index + 0.5, radius = c.f.radius_of();
        const double lo = std::max(-radius, -centre), hi = std::min(radius, c.size - centre);
        INFO((c.f.kind == WP_FILTER_TENT ? "tent radius " : "gaussian stddev ")
             << (c.f.kind == WP_FILTER_TENT ? c.f.radius : c.f.stddev) << ", pixel " << c.index
             << " of " << c.size << ": offsets in [" << lo << ", " << hi << "]");
        std::vector<float> offsets = filter_positions(c.f, c.index, c.size, seed++);
        for (float& x : offsets)
            x = static_cast<float>(x - centre);
        check_filter_samples(offsets, c.f, lo, hi);
    }
}
