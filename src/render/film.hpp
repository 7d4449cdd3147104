// The accumulated image: per-pixel sums in double precision on the host.
//
// The device adds samples into float32 buffers for a few waves at a time and
// the host folds them in here, so that a reference render of 65536 samples
// per pixel does not lose the small late samples to float32 rounding.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.hpp"

namespace wp {

class Film {
  public:
    Film() = default;
    Film(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    // Samples per pixel so far (every pixel gets the same number).
    std::uint64_t samples() const { return samples_; }
    std::uint64_t odd_samples() const { return odd_samples_; }

    // Adds a batch: per-pixel float4 sums (rgb + unused w) over `samples`
    // samples, `odd` of which had odd sample indices.
    void add_batch(const std::vector<float>& sum, const std::vector<float>& sum_squares,
                   const std::vector<float>& odd_sum, std::uint64_t samples, std::uint64_t odd);

    // Combines another film of disjoint samples (e.g. from another device).
    void merge(const Film& other);

    Image mean() const;                // the estimate: sum / samples
    Image variance_of_mean() const;    // per pixel and channel: sample variance / samples
    Image half_mean(int parity) const; // mean over even (0) or odd (1) sample indices

  private:
    int width_ = 0;
    int height_ = 0;
    std::uint64_t samples_ = 0;
    std::uint64_t odd_samples_ = 0;
    std::vector<double> sum_;         // rgb per pixel
    std::vector<double> sum_squares_; // rgb per pixel
    std::vector<double> odd_sum_;     // rgb per pixel, odd sample indices only
};

} // namespace wp
