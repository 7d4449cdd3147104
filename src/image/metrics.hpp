// Image error metrics for convergence reports: a render against a reference.
#pragma once

#include "image/image.hpp"

#include <cstddef>

namespace wp {

// Root mean squared error over all pixels and channels.
double rmse(const Image& a, const Image& ref);

// Relative MSE: mean over pixels and channels of (a - r)^2 / (r^2 + 0.01). The 0.01
// keeps black reference pixels from dominating, so dark and bright regions both count.
double rel_mse(const Image& a, const Image& ref);

// Number of NaN or infinite floats (channels, not pixels): a render with any is broken.
std::size_t count_nonfinite(const Image& img);

// rmse and rel_mse throw ImageError when the sizes differ or an image is empty.
// Non-finite values propagate into the result; check count_nonfinite first.

} // namespace wp
