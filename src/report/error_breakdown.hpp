// Where the error of a render is: the estimate split by path type
// (kernels/path_type.h), each part's share of the mean squared error, near
// the light and elsewhere (`wavepath breakdown`, docs/convergence.md).
//
// For an unbiased estimator the MSE of a pixel's mean of n independent
// samples is its variance / n, which the film estimates from its sums of
// squares, so no reference is needed. The parts X_1 + ... + X_5 = X of one
// seed come from the same paths and are correlated, so their variances do not
// add up to Var X; each part's share is its covariance with the whole,
// Cov(X_k, X) = (Var X + Var X_k - Var(X - X_k)) / 2, and these shares do sum
// to Var X (Cov is linear). It takes three renders of one seed: the full
// estimate, the part alone and the rest without it.
#pragma once

#include <cstddef>
#include <vector>

#include "image/image.hpp"

namespace wp {

// Per value: the part's share of the variance of the whole,
// (whole + part - rest) / 2, from three variance images of one seed (the
// whole, the part alone, everything but the part). Throws ImageError when the
// sizes differ.
Image variance_share(const Image& whole, const Image& part, const Image& rest);

// The pixels near the light: those whose brightest channel in `image` is
// above `threshold` (the light seen directly or in a mirror), grown by
// `radius` pixels in x and y (a square of side 2 radius + 1).
std::vector<bool> bright_region(const Image& image, double threshold, int radius);

// A sum over the pixels and channels of `values`, divided by the number of
// values of the whole image: `inside` over the region's pixels, `outside`
// over the rest, so inside + outside = total (a mean over the image).
struct RegionMeans {
    double total = 0.0;
    double inside = 0.0;
    double outside = 0.0;
};
RegionMeans region_means(const Image& values, const std::vector<bool>& region);

// The same for the squared difference (a - b)^2: the MSE of a against b.
RegionMeans region_squared_error(const Image& a, const Image& b, const std::vector<bool>& region);

// The fraction of pixels in a region.
double region_fraction(const std::vector<bool>& region);

} // namespace wp
