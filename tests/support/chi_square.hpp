// Pearson's chi-square goodness-of-fit test with its p-value, for the tests
// of sampling routines against their densities (tests/kernels).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace wp::test {

// The regularised upper incomplete gamma function Q(a, x) (series below
// a + 1, Lentz's continued fraction above), for chi-square p-values.
inline double gamma_q(double a, double x) {
    if (x <= 0.0)
        return 1.0;
    const double log_prefactor = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 1000 && std::fabs(term) > 1e-16 * std::fabs(sum); ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * std::exp(log_prefactor);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 1000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        d = std::fabs(d) < tiny ? tiny : d;
        c = b + an / c;
        c = std::fabs(c) < tiny ? tiny : c;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16)
            break;
    }
    return std::exp(log_prefactor) * h;
}

// The chi-square test's outcome.
struct ChiSquare {
    double statistic = 0.0;
    std::size_t dof = 0;
    double p_value = 0.0;
    std::size_t outside = 0; // samples in bins of zero expectation
};

// Pearson's test of observed against expected counts, bins of expectation
// below 5 pooled into one (Mitsuba's ChiSquareTest does the same).
inline ChiSquare chi_square(const std::vector<double>& observed,
                            const std::vector<double>& expected) {
    ChiSquare out;
    std::vector<std::size_t> order(observed.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
    double pooled_observed = 0.0, pooled_expected = 0.0;
    std::size_t bins = 0;
    for (std::size_t i : order) {
        if (expected[i] == 0.0) {
            out.outside += static_cast<std::size_t>(observed[i]);
            continue;
        }
        if (expected[i] < 5.0 || (pooled_expected > 0.0 && pooled_expected < 5.0)) {
            pooled_observed += observed[i];
            pooled_expected += expected[i];
            continue;
        }
        out.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++bins;
    }
    if (pooled_expected > 0.0) {
        out.statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) /
                         pooled_expected;
        ++bins;
    }
    out.dof = bins - 1;
    out.p_value = gamma_q(0.5 * double(out.dof), 0.5 * out.statistic);
    return out;
}

} // namespace wp::test
