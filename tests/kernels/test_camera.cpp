// The camera's sampling routines on the device (kernels/camera.h,
// kernels/sampling.h): the thin lens's concentric disk map and the tent and
// Gaussian pixel filters, each by a chi-square test of 2^20 samples against
// its density, integrated over each bin in double precision on the host.
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
    const double radius = f.kind == WP_FILTER_GAUSSIAN ? 4.0 * f.stddev : f.radius;
    const double scale = 1.0 / (f.stddev * std::sqrt(2.0));
    cl::Kernel kernel(program(kCameraSource, "camera_test.cl"), "filter_samples");
    cl::Buffer out = upload(std::vector<float>(kSamples));
    set_args(kernel, f.kind, static_cast<float>(radius), static_cast<float>(scale),
             static_cast<float>(std::exp(-(radius * scale) * (radius * scale))), seed, kSamples,
             out);
    launch(kernel, kSamples);
    return download<float>(out, kSamples);
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
        const double radius = f.kind == WP_FILTER_GAUSSIAN ? 4.0 * f.stddev : f.radius;
        INFO((f.kind == WP_FILTER_TENT ? "tent radius " : "gaussian stddev ")
             << (f.kind == WP_FILTER_TENT ? f.radius : f.stddev));
        const std::vector<float> samples = filter_samples(f, seed++);

        constexpr int kBins = 80;
        std::vector<double> observed(kBins, 0.0), expected(kBins);
        std::size_t outside = 0;
        for (float x : samples) {
            if (!(std::fabs(x) <= radius)) {
                ++outside;
                continue;
            }
            const int bin =
                std::min(kBins - 1, static_cast<int>((x + radius) / (2.0 * radius) * kBins));
            observed[bin] += 1.0;
        }
        CHECK(outside == 0);
        const double total = f.integral(-radius, radius);
        for (int i = 0; i < kBins; ++i) {
            const double a = -radius + 2.0 * radius * i / kBins;
            const double b = -radius + 2.0 * radius * (i + 1) / kBins;
            expected[i] = double(kSamples) * f.integral(a, b) / total;
        }
        const ChiSquare result = chi_square(observed, expected);
        INFO("chi-square " << result.statistic << " for " << result.dof << " degrees of freedom, p "
                           << result.p_value);
        CHECK(result.outside == 0);
        CHECK(result.p_value > kSignificance);

        // The samples' variance against the density's, within 5 standard
        // errors of the sample variance (a check of the tails, where the
        // histogram's bins pool).
        double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
        for (float x : samples) {
            sum += x;
            sum2 += double(x) * x;
            sum4 += double(x) * x * double(x) * x;
        }
        const double n = double(kSamples), m2 = sum2 / n;
        const double m2_error = std::sqrt((sum4 / n - m2 * m2) / n);
        double reference = 0.0; // the second moment, by Simpson's rule
        {
            constexpr int kSteps = 4096;
            const double h = 2.0 * radius / kSteps;
            for (int i = 0; i <= kSteps; ++i) {
                const double x = -radius + i * h;
                const double w = (i == 0 || i == kSteps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
                reference += w * x * x * f.eval(x);
            }
            reference *= h / 3.0 / total;
        }
        INFO("second moment " << m2 << " +- " << m2_error << ", expected " << reference << "; mean "
                              << sum / n);
        CHECK(std::fabs(m2 - reference) <= 5.0 * m2_error);
        CHECK(std::fabs(sum / n) <= 5.0 * std::sqrt(m2 / n));
    }
}
