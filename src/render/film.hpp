// The accumulated image: per-pixel sums in double precision on the host.
//
// The device adds samples into float32 buffers for a few dozen iterations at
// a time and the host folds them in here, so that a reference render of
// 65536 samples per pixel does not lose its late samples to float32 rounding.
// Pixels keep their own sample counts: with path regeneration they finish
// samples at different times, and a progressive render may stop in between.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.hpp"

namespace wp {

// A film's raw sums and counts, for saving a render and resuming it
// (render/checkpoint.hpp). The layout of Film's own arrays.
struct FilmSums {
    std::vector<double> sum;         // rgb per pixel
    std::vector<double> sum_squares; // rgb per pixel
    std::vector<double> odd_sum;     // rgb per pixel, odd sample indices only
    std::vector<std::uint64_t> count;
    std::vector<std::uint64_t> odd_count;
    // The AOVs' sums (albedo rgb, normal xyz, depth: 7 per pixel), or empty
    // for a film without AOVs (add_aov_batch).
    std::vector<double> aov_sum = {};
};

class Film {
  public:
    Film() = default;
    Film(int width, int height);
    // A film holding saved sums; throws std::invalid_argument unless the
    // arrays have the sizes of a width x height film.
    Film(int width, int height, FilmSums sums);

    int width() const { return width_; }
    int height() const { return height_; }
    std::size_t pixel_count() const { return count_.size(); }
    // Samples of one pixel so far, and the fewest of any pixel (the spp of a
    // finished render).
    std::uint64_t samples(std::size_t pixel) const { return count_[pixel]; }
    std::uint64_t min_samples() const;
    std::uint64_t total_samples() const;

    // Adds a batch read from the device: per pixel a float4 whose rgb is a sum
    // and whose w is the number of samples in it (sum of squares: w unused;
    // odd: sums and count over odd sample indices only).
    void add_batch(const std::vector<float>& sum, const std::vector<float>& sum_squares,
                   const std::vector<float>& odd_sum);

    // Adds a batch of the AOVs' sums read from the device (kernels/shade.cl,
    // WP_AOV): per pixel, a float4 of albedo (rgb), a float4 of the shading
    // normal (xyz) and a float of depth, each summed over the batch's samples
    // (which the film's counts count). The film holds AOVs from its first
    // such batch (or merge) on.
    void add_aov_batch(const std::vector<float>& albedo, const std::vector<float>& normal,
                       const std::vector<float>& depth);
    bool has_aovs() const { return !aov_sum_.empty(); }

    // Combines another film of disjoint samples (e.g. from another device),
    // AOVs included.
    void merge(const Film& other);

    // Everything the film holds, to be given back to the constructor above
    // (a checkpoint, or another MPI rank's film).
    FilmSums sums() const { return {sum_, sum_squares_, odd_sum_, count_, odd_count_, aov_sum_}; }

    Image mean() const;                // the estimate: sum / samples, per pixel
    Image variance_of_mean() const;    // per pixel and channel: sample variance / samples
    Image half_mean(int parity) const; // mean over even (0) or odd (1) sample indices
    // The mean over each pixel's samples of AOV `number` (0 albedo, 1 normal,
    // 2 depth; kAov* in render/integrator_options.hpp), interleaved: 3
    // values a pixel (1 for depth); 0 for a pixel without samples or a film
    // without AOVs.
    std::vector<float> aov_mean(std::uint32_t number) const;

  private:
    int width_ = 0;
    int height_ = 0;
    std::vector<double> sum_;         // rgb per pixel
    std::vector<double> sum_squares_; // rgb per pixel
    std::vector<double> odd_sum_;     // rgb per pixel, odd sample indices only
    std::vector<std::uint64_t> count_;
    std::vector<std::uint64_t> odd_count_;
    // The AOVs' sums: albedo rgb, normal xyz, depth per pixel (7 a pixel), or
    // empty for a film without AOVs.
    std::vector<double> aov_sum_;
};

} // namespace wp
