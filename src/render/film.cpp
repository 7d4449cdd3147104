#include "render/film.hpp"

#include <algorithm>
#include <stdexcept>

namespace wp {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(static_cast<std::size_t>(width) * height * 3, 0.0),
      sum_squares_(sum_.size(), 0.0), odd_sum_(sum_.size(), 0.0) {}

void Film::add_batch(const std::vector<float>& sum, const std::vector<float>& sum_squares,
                     const std::vector<float>& odd_sum, std::uint64_t samples, std::uint64_t odd) {
    std::size_t pixels = sum_.size() / 3;
    if (sum.size() != pixels * 4 || sum_squares.size() != pixels * 4 ||
        odd_sum.size() != pixels * 4)
        throw std::logic_error("Film::add_batch: buffer size does not match the film");
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            sum_[p * 3 + c] += sum[p * 4 + c];
            sum_squares_[p * 3 + c] += sum_squares[p * 4 + c];
            odd_sum_[p * 3 + c] += odd_sum[p * 4 + c];
        }
    samples_ += samples;
    odd_samples_ += odd;
}

void Film::merge(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        throw std::logic_error("Film::merge: films differ in size");
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        sum_[i] += other.sum_[i];
        sum_squares_[i] += other.sum_squares_[i];
        odd_sum_[i] += other.odd_sum_[i];
    }
    samples_ += other.samples_;
    odd_samples_ += other.odd_samples_;
}

Image Film::mean() const {
    Image image(width_, height_);
    double scale = samples_ ? 1.0 / static_cast<double>(samples_) : 0.0;
    for (std::size_t i = 0; i < sum_.size(); ++i)
        image.rgb[i] = static_cast<float>(sum_[i] * scale);
    return image;
}

Image Film::variance_of_mean() const {
    Image image(width_, height_);
    if (samples_ < 2)
        return image;
    double n = static_cast<double>(samples_);
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        double mean = sum_[i] / n;
        double variance = (sum_squares_[i] / n - mean * mean) * n / (n - 1.0);
        image.rgb[i] = static_cast<float>(std::max(0.0, variance) / n);
    }
    return image;
}

Image Film::half_mean(int parity) const {
    Image image(width_, height_);
    std::uint64_t count = parity ? odd_samples_ : samples_ - odd_samples_;
    if (count == 0)
        return image;
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        double s = parity ? odd_sum_[i] : sum_[i] - odd_sum_[i];
        image.rgb[i] = static_cast<float>(s / static_cast<double>(count));
    }
    return image;
}

} // namespace wp
