#include "render/environment_tables.hpp"
#include "scene/luminance.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wp {
namespace {

constexpr double kPi = std::numbers::pi;

// cos(theta_j) - cos(theta_{j+1}), theta_j = pi j / rows (the kernels' form).
double cos_span(std::uint32_t j, std::uint32_t rows) {
    return 2.0 * std::sin(kPi * (j + 0.5) / rows) * std::sin(0.5 * kPi / rows);
}

// Fills `out` (n entries) with the cumulative sums of `weights` over their
// total as floats ending in exactly 1; uniform steps when the total is 0.
void cumulative(const double* weights, std::size_t n, float* out) {
    double total = 0.0;
    for (std::size_t k = 0; k < n; ++k)
        total += weights[k];
    double running = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        running += total > 0.0 ? weights[k] : 1.0;
        out[k] = static_cast<float>(running / (total > 0.0 ? total : static_cast<double>(n)));
    }
    out[n - 1] = 1.0f;
}

} // namespace

glm::dvec3 EnvironmentTables::texel(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void environment_patch(std::uint32_t width, std::uint32_t height, const glm::dvec3& local,
                       std::uint32_t* i, std::uint32_t* j, double* ax, double* ay) {
    double u = std::atan2(local.x, -local.z) / (2.0 * kPi);
    u -= std::floor(u);
    const double v = std::acos(std::clamp(local.y, -1.0, 1.0)) / kPi;
    const double x = u * width - 0.5;
    const double x_floor = std::floor(x);
    *ax = x - x_floor;
    *i = x_floor < 0.0 ? width - 1 : static_cast<std::uint32_t>(x_floor);
    const double y = v * (height - 1);
    const double y_floor = std::min(std::floor(y), static_cast<double>(height - 2));
    *j = static_cast<std::uint32_t>(y_floor);
    *ay = y - y_floor;
}

glm::dvec3 EnvironmentTables::radiance(const glm::dvec3& local) const {
    std::uint32_t i, j;
    double ax, ay;
    environment_patch(width, height, local, &i, &j, &ax, &ay);
    const std::uint32_t i1 = i + 1 == width ? 0 : i + 1;
    const glm::dvec3 top = (1.0 - ax) * texel(i, j) + ax * texel(i1, j);
    const glm::dvec3 bottom = (1.0 - ax) * texel(i, j + 1) + ax * texel(i1, j + 1);
    return (1.0 - ay) * top + ay * bottom;
}

double EnvironmentTables::pdf(const glm::dvec3& local) const {
    if (cdf.empty())
        return 0.0;
    std::uint32_t i, j;
    double ax, ay;
    environment_patch(width, height, local, &i, &j, &ax, &ay);
    const std::uint32_t rows = height - 1;
    const float* marginal = cdf.data();
    const float* row = marginal + rows + static_cast<std::size_t>(j) * width;
    // The float tables' differences, as the kernels take them.
    const double p_row = static_cast<double>(marginal[j]) - (j > 0 ? marginal[j - 1] : 0.0f);
    const double p_column = static_cast<double>(row[i]) - (i > 0 ? row[i - 1] : 0.0f);
    return p_row * p_column / (2.0 * kPi / width * cos_span(j, rows));
}

EnvironmentTables build_environment_tables(const TextureImage& image) {
    EnvironmentTables t;
    t.width = std::max(image.width, 2u);
    t.height = std::max(image.height, 3u);
    t.rgb.resize(3 * static_cast<std::size_t>(t.width) * t.height);
    for (std::uint32_t y = 0; y < t.height; ++y)
        for (std::uint32_t x = 0; x < t.width; ++x) {
            const glm::dvec3 c =
                linear_texel(image, std::min(x, image.width - 1), std::min(y, image.height - 1));
            float* out = &t.rgb[3 * (static_cast<std::size_t>(y) * t.width + x)];
            out[0] = static_cast<float>(c.x);
            out[1] = static_cast<float>(c.y);
            out[2] = static_cast<float>(c.z);
        }
    // Each patch's weight: its corners' mean luminance times its solid
    // angle; the tables row by row, so that no table of doubles as large as
    // the image is ever held (a 16384 x 8192 map has 134 million patches).
    const std::uint32_t w = t.width, rows = t.height - 1;
    auto corners = [&](std::uint32_t i, std::uint32_t j, auto value) {
        const std::uint32_t i1 = i + 1 == w ? 0 : i + 1;
        return 0.25 * (value(t.texel(i, j)) + value(t.texel(i1, j)) + value(t.texel(i, j + 1)) +
                       value(t.texel(i1, j + 1)));
    };
    auto mean = [](const glm::dvec3& c) { return (c.x + c.y + c.z) / 3.0; };
    t.cdf.resize(rows + static_cast<std::size_t>(w) * rows);
    std::vector<double> row_weights(rows), weights(w);
    for (std::uint32_t j = 0; j < rows; ++j) {
        const double solid_angle = 2.0 * kPi / w * cos_span(j, rows);
        for (std::uint32_t i = 0; i < w; ++i) {
            weights[i] = corners(i, j, luminance) * solid_angle;
            row_weights[j] += weights[i];
            t.integral += corners(i, j, mean) * solid_angle;
        }
        cumulative(weights.data(), w, &t.cdf[rows + static_cast<std::size_t>(j) * w]);
    }
    double total = 0.0;
    for (double r : row_weights)
        total += r;
    if (!(total > 0.0)) { // black: never sampled, and it adds nothing where it is seen
        t.cdf.clear();
        return t;
    }
    cumulative(row_weights.data(), rows, t.cdf.data());
    // Each row's cos(theta_j) and cos(theta_j) - cos(theta_{j+1}), which the
    // kernels' sample and density read instead of computing them (two
    // polynomials, their divisions and a call: 8 % of the showcase's shade).
    t.cdf.reserve(t.cdf.size() + 2 * static_cast<std::size_t>(rows));
    for (std::uint32_t j = 0; j < rows; ++j) {
        t.cdf.push_back(static_cast<float>(std::cos(kPi * j / rows)));
        t.cdf.push_back(static_cast<float>(cos_span(j, rows)));
    }
    return t;
}

} // namespace wp
