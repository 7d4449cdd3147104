// `wavepath compare`: error metrics of an image against a reference, and a
// false-colour map of where the error is (docs/convergence.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "util/file.hpp"

namespace wp {
namespace {

// The false-colour scale: log10 of the per-pixel relative squared error from
// kLogMin (black) to kLogMax (light yellow), through the "inferno" colour map.
constexpr double kLogMin = -4.0, kLogMax = 0.0;
constexpr std::array<std::array<double, 3>, 6> kInferno = {
    {{0, 0, 4}, {66, 10, 104}, {147, 38, 103}, {221, 81, 58}, {252, 165, 10}, {252, 255, 164}}};

// An 8-bit sRGB value as the linear value that write_png's sRGB view maps back to it.
float srgb_to_linear(double value8) {
    const double v = value8 / 255.0;
    return static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

Image false_colour(const Image& map) {
    Image out(map.width, map.height);
    for (std::size_t p = 0; p < map.rgb.size(); p += 3) {
        const double e = static_cast<double>(map.rgb[p]);
        std::array<double, 3> colour{255, 0, 255}; // magenta: NaN or Inf
        if (std::isfinite(e)) {
            const double l = e > 0.0 ? std::log10(e) : kLogMin;
            const double t = std::clamp((l - kLogMin) / (kLogMax - kLogMin), 0.0, 1.0) *
                             static_cast<double>(kInferno.size() - 1);
            const auto i = std::min(static_cast<std::size_t>(t), kInferno.size() - 2);
            const double f = t - static_cast<double>(i);
            for (std::size_t c = 0; c < 3; ++c)
                colour[c] = kInferno[i][c] + f * (kInferno[i + 1][c] - kInferno[i][c]);
        }
        for (std::size_t c = 0; c < 3; ++c)
            out.rgb[p + c] = srgb_to_linear(colour[c]);
    }
    return out;
}

// The block size of the z-test: small enough to see a wrong region, large
// enough that a block's mean is near normal at a few samples per pixel.
constexpr int kBlock = 16;

struct ZTest {
    std::array<double, 3> whole{}; // z of the whole image's mean difference, per channel
    double largest_block = 0.0;    // the largest |z| of any block and channel
    int blocks = 0;
    int blocks_beyond = 0; // blocks with some channel's |z| above the limit
};

// z = (sum of x - r) / sqrt(sum of both variances of the mean) over a region;
// 0 where the region has no difference and no variance, infinite where it has
// a difference but no variance.
double z_score(double difference, double variance) {
    if (variance > 0.0)
        return difference / std::sqrt(variance);
    return difference == 0.0 ? 0.0 : difference * std::numeric_limits<double>::infinity();
}

ZTest z_test(const Image& image, const Image& reference, const Image& image_variance,
             const Image& reference_variance, double sigma) {
    ZTest test;
    std::array<double, 3> difference{}, variance{};
    for (int by = 0; by < image.height; by += kBlock)
        for (int bx = 0; bx < image.width; bx += kBlock) {
            std::array<double, 3> d{}, v{};
            for (int y = by; y < std::min(by + kBlock, image.height); ++y)
                for (int x = bx; x < std::min(bx + kBlock, image.width); ++x)
                    for (std::size_t c = 0; c < 3; ++c) {
                        const std::size_t i =
                            (static_cast<std::size_t>(y) * image.width + x) * 3 + c;
                        d[c] += double(image.rgb[i]) - double(reference.rgb[i]);
                        v[c] += double(image_variance.rgb[i]) + double(reference_variance.rgb[i]);
                    }
            bool beyond = false;
            for (std::size_t c = 0; c < 3; ++c) {
                const double z = std::abs(z_score(d[c], v[c]));
                test.largest_block = std::max(test.largest_block, z);
                beyond = beyond || !(z <= sigma);
                difference[c] += d[c];
                variance[c] += v[c];
            }
            ++test.blocks;
            test.blocks_beyond += beyond;
        }
    for (std::size_t c = 0; c < 3; ++c)
        test.whole[c] = z_score(difference[c], variance[c]);
    return test;
}

} // namespace

CLI::App* add_compare_subcommand(CLI::App& app, CompareCommand& command) {
    CLI::App* c = app.add_subcommand(
        "compare", "Print RMSE, relMSE, mean relative bias per channel and NaN/Inf counts of an "
                   "image against a reference (.exr or .pfm); optionally write an error map");
    c->add_option("image", command.image, "The image to judge")->required();
    c->add_option("reference", command.reference, "The reference (same size)")->required();
    c->add_option("--diff", command.diff,
                  "Write the per-pixel relative squared error, (x - r)^2 / (r^2 + 0.01) "
                  "averaged over channels: .png as false colour (log scale, 1e-4 black to 1 "
                  "yellow, NaN/Inf magenta), .exr/.pfm as raw values");
    c->add_option("--variance", command.variances,
                  "The image's and the reference's variances of the mean (render --variance): "
                  "test that they differ by noise alone, the whole image and each 16x16 block "
                  "within --sigma standard errors per channel; exit status 1 if not")
        ->expected(2);
    c->add_option("--sigma", command.sigma, "The z-test's limit, in standard errors")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    return c;
}

int run_compare(const CompareCommand& command) {
    check_output(command.diff, kImageExtensions);
    check_distinct_outputs({{"the image", command.image}, {"the reference", command.reference}},
                           {{"--diff", command.diff}});
    const Image image = read_image(command.image);
    const Image reference = read_image(command.reference);
    if (image.width != reference.width || image.height != reference.height)
        throw ImageError("'" + command.image + "' is " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " but '" + command.reference + "' is " +
                         std::to_string(reference.width) + "x" + std::to_string(reference.height));

    std::vector<Image> variances;
    for (const std::string& path : command.variances) {
        variances.push_back(read_image(path));
        if (variances.back().width != image.width || variances.back().height != image.height)
            throw ImageError("'" + path + "' is " + std::to_string(variances.back().width) + "x" +
                             std::to_string(variances.back().height) + " but '" + command.image +
                             "' is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height));
    }

    const std::array<double, 3> bias = mean_relative_bias(image, reference);
    std::printf("image      %s (%dx%d)\nreference  %s\n", command.image.c_str(), image.width,
                image.height, command.reference.c_str());
    std::printf("RMSE       %.6g\n", rmse(image, reference));
    std::printf("relMSE     %.6g\n", rel_mse(image, reference));
    std::printf("mean relative bias  R %+.4f%%  G %+.4f%%  B %+.4f%%\n", 100.0 * bias[0],
                100.0 * bias[1], 100.0 * bias[2]);
    std::printf("NaN/Inf    image %zu, reference %zu\n", count_nonfinite(image),
                count_nonfinite(reference));
    std::size_t identical = 0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
        identical += std::memcmp(&image.rgb[i], &reference.rgb[i], sizeof(float)) == 0;
    std::printf("identical  %zu of %zu values, bit for bit\n", identical, image.rgb.size());
    int status = 0;
    if (variances.size() == 2) {
        const ZTest z = z_test(image, reference, variances[0], variances[1], command.sigma);
        const bool pass = z.blocks_beyond == 0 && std::abs(z.whole[0]) <= command.sigma &&
                          std::abs(z.whole[1]) <= command.sigma &&
                          std::abs(z.whole[2]) <= command.sigma;
        std::printf("z-test     whole image R %+.2f G %+.2f B %+.2f; %d of %d blocks of %dx%d "
                    "beyond %g sigma (largest |z| %.2f): %s\n",
                    z.whole[0], z.whole[1], z.whole[2], z.blocks_beyond, z.blocks, kBlock, kBlock,
                    command.sigma, z.largest_block, pass ? "pass" : "FAIL");
        status = pass ? 0 : 1;
    }

    if (!command.diff.empty()) {
        const Image map = rel_error_map(image, reference);
        if (lower_extension(command.diff) == ".png") {
            // The false colours are display values: shown as they are, never exposed.
            write_image(command.diff, false_colour(map), ViewOptions::fixed(0.0));
            std::printf("wrote %s: log10 relative squared error, %g (black) to %g (yellow); "
                        "magenta: NaN/Inf\n",
                        command.diff.c_str(), kLogMin, kLogMax);
        } else {
            write_image(command.diff, map);
            std::printf("wrote %s: relative squared error per pixel\n", command.diff.c_str());
        }
    }
    return status;
}

} // namespace wp
