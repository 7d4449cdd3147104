// Image error metrics for convergence reports: a render against a reference.
#pragma once

#include "image/image.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace wp {

// Root mean squared error over all pixels and channels.
double rmse(const Image& a, const Image& ref);

// Relative MSE: mean over pixels and channels of (a - r)^2 / (r^2 + 0.01). The 0.01
// keeps black reference pixels from dominating, so dark and bright regions both count.
double rel_mse(const Image& a, const Image& ref);

// Number of NaN or infinite floats (channels, not pixels): a render with any is broken.
std::size_t count_nonfinite(const Image& img);

// Mean squared error over all pixels and channels (rmse squared).
double mse(const Image& a, const Image& ref);

// Per channel c: (mean of a_c - mean of ref_c) / mean of ref_c, the means over all
// pixels. A ratio of means, not a mean of per-pixel ratios, so dark pixels do not
// dominate. NaN for a channel whose reference mean is 0.
std::array<double, 3> mean_relative_bias(const Image& a, const Image& ref);

// The error of a Monte Carlo estimate without a reference, from two independent
// half estimates: `even` and `odd` average disjoint sets of samples (even and odd
// sample indices: n_even and n_odd of them per pixel, both > 0). For one pixel the
// full mean m has Var(m) = s^2 / n, and Var(even - odd) = s^2 (1/n_even + 1/n_odd),
// so (even - odd)^2 * n_even n_odd / n^2 is an unbiased estimate of Var(m); with
// n_even = n_odd it is (even - odd)^2 / 4. mse_from_halves averages it over pixels
// and channels: the expected MSE of the full mean against the true image (for an
// unbiased estimator).
double mse_from_halves(const Image& even, const Image& odd, std::uint64_t n_even,
                       std::uint64_t n_odd);

// The same per-value variance estimate v divided by (r^2 + 0.01) as in rel_mse,
// averaged: an estimate of the relative MSE against the unknown true image r, with r
// estimated by the 3x3 box mean of the full mean m = (n_even even + n_odd odd) / n.
// The box keeps one outlier (a dark pixel with one bright sample) from inflating its
// own denominator, which the plug-in m^2 does badly: it divides exactly the largest
// errors by the largest values (on the hexroom at 32x32 it read 0.06 times the true
// relMSE at 16 spp). Still a plug-in, measured against the true relMSE on the
// hexroom at 32x32: 0.34, 0.63 and 0.85 times it at 16, 64 and 256 spp with
// next-event estimation (rare bright samples in dark pixels dominate), 0.48, 0.97
// and 0.96 without. Prefer a reference when relMSE matters.
double rel_mse_from_halves(const Image& even, const Image& odd, std::uint64_t n_even,
                           std::uint64_t n_odd);

// Per pixel, the mean over channels of (a - r)^2 / (r^2 + 0.01): the terms whose
// mean is rel_mse, as a one-channel map (stored in every channel). NaN where a or
// ref is not finite.
Image rel_error_map(const Image& a, const Image& ref);

// Every metric of two images throws ImageError when the sizes differ or an image is
// empty; mse_from_halves also when a sample count is 0.
// Non-finite values propagate into the result; check count_nonfinite first.

} // namespace wp
