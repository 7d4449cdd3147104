// `wavepath compare`: error metrics of an image against a reference, and a
// false-colour map of where the error is (docs/convergence.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

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

    const std::array<double, 3> bias = mean_relative_bias(image, reference);
    std::printf("image      %s (%dx%d)\nreference  %s\n", command.image.c_str(), image.width,
                image.height, command.reference.c_str());
    std::printf("RMSE       %.6g\n", rmse(image, reference));
    std::printf("relMSE     %.6g\n", rel_mse(image, reference));
    std::printf("mean relative bias  R %+.4f%%  G %+.4f%%  B %+.4f%%\n", 100.0 * bias[0],
                100.0 * bias[1], 100.0 * bias[2]);
    std::printf("NaN/Inf    image %zu, reference %zu\n", count_nonfinite(image),
                count_nonfinite(reference));

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
    return 0;
}

} // namespace wp
