#include "render/film.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace wp {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(static_cast<std::size_t>(width) * height * 3, 0.0),
      sum_squares_(sum_.size(), 0.0), odd_sum_(sum_.size(), 0.0), count_(sum_.size() / 3, 0),
      odd_count_(count_.size(), 0) {}

Film::Film(int width, int height, FilmSums sums)
    : width_(width), height_(height), sum_(std::move(sums.sum)),
      sum_squares_(std::move(sums.sum_squares)), odd_sum_(std::move(sums.odd_sum)),
      count_(std::move(sums.count)), odd_count_(std::move(sums.odd_count)),
      aov_sum_(std::move(sums.aov_sum)) {
    const std::size_t pixels =
        width > 0 && height > 0 ? static_cast<std::size_t>(width) * height : 0;
    if (pixels == 0 || sum_.size() != pixels * 3 || sum_squares_.size() != pixels * 3 ||
        odd_sum_.size() != pixels * 3 || count_.size() != pixels || odd_count_.size() != pixels ||
        (!aov_sum_.empty() && aov_sum_.size() != pixels * 7))
        throw std::invalid_argument("Film: the saved sums do not match a " + std::to_string(width) +
                                    "x" + std::to_string(height) + " film");
}

std::uint64_t Film::min_samples() const {
    return count_.empty() ? 0 : *std::min_element(count_.begin(), count_.end());
}

std::uint64_t Film::total_samples() const {
    return std::accumulate(count_.begin(), count_.end(), std::uint64_t{0});
}

void Film::add_batch(const std::vector<float>& sum, const std::vector<float>& sum_squares,
                     const std::vector<float>& odd_sum) {
    const std::size_t pixels = count_.size();
    if (sum.size() != pixels * 4 || sum_squares.size() != pixels * 4 ||
        odd_sum.size() != pixels * 4)
        throw std::logic_error("Film::add_batch: buffer size does not match the film");
    for (std::size_t p = 0; p < pixels; ++p) {
        for (std::size_t c = 0; c < 3; ++c) {
            sum_[p * 3 + c] += sum[p * 4 + c];
            sum_squares_[p * 3 + c] += sum_squares[p * 4 + c];
            odd_sum_[p * 3 + c] += odd_sum[p * 4 + c];
        }
        // Counts travel as floats: exact, as a batch holds far fewer than 2^24.
        count_[p] += static_cast<std::uint64_t>(sum[p * 4 + 3]);
        odd_count_[p] += static_cast<std::uint64_t>(odd_sum[p * 4 + 3]);
    }
}

namespace {
constexpr std::size_t kAovValues = 7; // albedo rgb, normal xyz, depth per pixel
}

void Film::add_aov_batch(const std::vector<float>& albedo, const std::vector<float>& normal,
                         const std::vector<float>& depth) {
    const std::size_t pixels = count_.size();
    if (albedo.size() != pixels * 4 || normal.size() != pixels * 4 || depth.size() != pixels)
        throw std::logic_error("Film::add_aov_batch: buffer size does not match the film");
    if (aov_sum_.empty())
        aov_sum_.assign(pixels * kAovValues, 0.0);
    for (std::size_t p = 0; p < pixels; ++p) {
        double* sum = &aov_sum_[p * kAovValues];
        for (std::size_t c = 0; c < 3; ++c) {
            sum[c] += albedo[p * 4 + c];
            sum[3 + c] += normal[p * 4 + c];
        }
        sum[6] += depth[p];
    }
}

std::vector<float> Film::aov_mean(std::uint32_t number) const {
    const std::size_t channels = number == 2 ? 1 : 3, first = number * 3;
    std::vector<float> mean(count_.size() * channels, 0.0f);
    if (aov_sum_.empty())
        return mean;
    for (std::size_t p = 0; p < count_.size(); ++p) {
        if (count_[p] == 0)
            continue;
        for (std::size_t c = 0; c < channels; ++c)
            mean[p * channels + c] = static_cast<float>(aov_sum_[p * kAovValues + first + c] /
                                                        static_cast<double>(count_[p]));
    }
    return mean;
}

void Film::merge(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        throw std::logic_error("Film::merge: films differ in size");
    if (!other.aov_sum_.empty()) {
        if (aov_sum_.empty())
            aov_sum_.assign(other.aov_sum_.size(), 0.0);
        for (std::size_t i = 0; i < aov_sum_.size(); ++i)
            aov_sum_[i] += other.aov_sum_[i];
    }
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        sum_[i] += other.sum_[i];
        sum_squares_[i] += other.sum_squares_[i];
        odd_sum_[i] += other.odd_sum_[i];
    }
    for (std::size_t p = 0; p < count_.size(); ++p) {
        count_[p] += other.count_[p];
        odd_count_[p] += other.odd_count_[p];
    }
}

Image Film::mean() const {
    Image image(width_, height_);
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        std::uint64_t n = count_[i / 3];
        image.rgb[i] = n ? static_cast<float>(sum_[i] / static_cast<double>(n)) : 0.0f;
    }
    return image;
}

Image Film::variance_of_mean() const {
    Image image(width_, height_);
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        double n = static_cast<double>(count_[i / 3]);
        if (n < 2.0)
            continue;
        double mean = sum_[i] / n;
        double variance = (sum_squares_[i] / n - mean * mean) * n / (n - 1.0);
        image.rgb[i] = static_cast<float>(std::max(0.0, variance) / n);
    }
    return image;
}

Image Film::half_mean(int parity) const {
    Image image(width_, height_);
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        std::size_t p = i / 3;
        std::uint64_t n = parity ? odd_count_[p] : count_[p] - odd_count_[p];
        double s = parity ? odd_sum_[i] : sum_[i] - odd_sum_[i];
        image.rgb[i] = n ? static_cast<float>(s / static_cast<double>(n)) : 0.0f;
    }
    return image;
}

} // namespace wp
