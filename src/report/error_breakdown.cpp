#include "report/error_breakdown.hpp"

#include <algorithm>
#include <string>

#include "image/image.hpp"

namespace wp {
namespace {

void check_same_size(const Image& a, const Image& b, const char* what) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
        throw ImageError(std::string(what) + ": the images differ in size (" +
                         std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                         std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

void check_region(const Image& image, const std::vector<bool>& region) {
    if (region.size() != image.rgb.size() / 3)
        throw ImageError("region_means: the region does not match the image's pixels");
}

} // namespace

Image variance_share(const Image& whole, const Image& part, const Image& rest) {
    check_same_size(whole, part, "variance_share");
    check_same_size(whole, rest, "variance_share");
    Image share(whole.width, whole.height);
    for (std::size_t i = 0; i < whole.rgb.size(); ++i)
        share.rgb[i] = static_cast<float>(
            (static_cast<double>(whole.rgb[i]) + part.rgb[i] - static_cast<double>(rest.rgb[i])) /
            2.0);
    return share;
}

std::vector<bool> bright_region(const Image& image, double threshold, int radius) {
    const int w = image.width, h = image.height;
    std::vector<bool> bright(static_cast<std::size_t>(w) * h, false);
    for (std::size_t p = 0; p < bright.size(); ++p)
        bright[p] =
            std::max({image.rgb[p * 3], image.rgb[p * 3 + 1], image.rgb[p * 3 + 2]}) > threshold;
    std::vector<bool> grown(bright.size(), false);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!bright[static_cast<std::size_t>(y) * w + x])
                continue;
            for (int yy = std::max(0, y - radius); yy <= std::min(h - 1, y + radius); ++yy)
                for (int xx = std::max(0, x - radius); xx <= std::min(w - 1, x + radius); ++xx)
                    grown[static_cast<std::size_t>(yy) * w + xx] = true;
        }
    return grown;
}

RegionMeans region_means(const Image& values, const std::vector<bool>& region) {
    check_region(values, region);
    RegionMeans means;
    for (std::size_t i = 0; i < values.rgb.size(); ++i)
        (region[i / 3] ? means.inside : means.outside) += values.rgb[i];
    const double n = static_cast<double>(values.rgb.size());
    means.inside /= n;
    means.outside /= n;
    means.total = means.inside + means.outside;
    return means;
}

RegionMeans region_squared_error(const Image& a, const Image& b, const std::vector<bool>& region) {
    check_same_size(a, b, "region_squared_error");
    check_region(a, region);
    RegionMeans means;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double d = static_cast<double>(a.rgb[i]) - b.rgb[i];
        (region[i / 3] ? means.inside : means.outside) += d * d;
    }
    const double n = static_cast<double>(a.rgb.size());
    means.inside /= n;
    means.outside /= n;
    means.total = means.inside + means.outside;
    return means;
}

double region_fraction(const std::vector<bool>& region) {
    if (region.empty())
        return 0.0;
    return static_cast<double>(std::count(region.begin(), region.end(), true)) /
           static_cast<double>(region.size());
}

} // namespace wp
