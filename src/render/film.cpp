#include "render/film.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace wp {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(static_cast<std::size_t>(width) * height * 3, 0.0),
      sum_squares_(sum_.size(), 0.0), odd_sum_(sum_.size(), 0.0), count_(sum_.size() / 3, 0),
      odd_count_(count_.size(), 0) {}

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

void Film::merge(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        throw std::logic_error("Film::merge: films differ in size");
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

std::vector<double> Film::packed_sums() const {
    std::vector<double> out(sum_);
    out.insert(out.end(), sum_squares_.begin(), sum_squares_.end());
    out.insert(out.end(), odd_sum_.begin(), odd_sum_.end());
    return out;
}

std::vector<std::uint64_t> Film::packed_counts() const {
    std::vector<std::uint64_t> out(count_);
    out.insert(out.end(), odd_count_.begin(), odd_count_.end());
    return out;
}

Film Film::from_packed(int width, int height, const std::vector<double>& sums,
                       const std::vector<std::uint64_t>& counts) {
    Film film(width, height);
    const std::size_t n = film.sum_.size(), pixels = film.count_.size();
    if (sums.size() != 3 * n || counts.size() != 2 * pixels)
        throw std::logic_error("Film::from_packed: sizes do not match the film");
    std::copy(sums.begin(), sums.begin() + static_cast<std::ptrdiff_t>(n), film.sum_.begin());
    std::copy(sums.begin() + static_cast<std::ptrdiff_t>(n),
              sums.begin() + static_cast<std::ptrdiff_t>(2 * n), film.sum_squares_.begin());
    std::copy(sums.begin() + static_cast<std::ptrdiff_t>(2 * n), sums.end(), film.odd_sum_.begin());
    std::copy(counts.begin(), counts.begin() + static_cast<std::ptrdiff_t>(pixels),
              film.count_.begin());
    std::copy(counts.begin() + static_cast<std::ptrdiff_t>(pixels), counts.end(),
              film.odd_count_.begin());
    return film;
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
