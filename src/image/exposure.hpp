// Automatic exposure: the exposure a view of a linear image needs, chosen from
// the image itself so that the first PNG of a scene is neither blown out nor
// black, whatever the scene's units.
#pragma once

#include "image/image.hpp"

namespace wp {

// Rec. 709 / sRGB luminance of linear RGB (the primaries the renderer's
// colours are read in).
double luminance(double r, double g, double b);

// What the automatic exposure saw. The scales multiply linear values;
// infinity where a statistic is 0 and so sets no bound.
struct AutoExposure {
    double scale = 1.0;           // min(key_scale, highlight_scale); 1 when neither bounds it
    double key_scale = 1.0;       // maps the median luminance to kMidGrey
    double highlight_scale = 1.0; // maps the high quantile of the brightest channel to 1
    std::size_t counted = 0;      // pixels that entered the statistics
    std::size_t emitters = 0;     // pixels left out as directly seen emitters
};

// The median luminance of the counted pixels becomes this mid grey (the 18 %
// grey card of photography; sRGB shows it at 118 of 255).
inline constexpr double kMidGrey = 0.18;
// At most 1 - kHighlightQuantile of the counted pixels may have a channel
// past 1 (clipped in the sRGB view).
inline constexpr double kHighlightQuantile = 0.99;

// The exposure scale for img. Counted are the pixels with finite, positive
// luminance below emitter_luminance: pixels at or above it see an emitter
// directly or in a mirror and would otherwise pull the exposure down for a
// light the view shows white anyway (pass infinity when unknown). Black
// pixels (no light found yet, or the world outside a room) carry no
// information about exposure and are not counted either.
//
// The statistics are taken of the image through a 3x3 median filter (over
// the pixels that are not emitters), which removes the isolated bright
// pixels that few samples per pixel leave where light comes by way of
// mirrors: at 8 samples per pixel they are several percent of the hexroom
// and would otherwise set the highlight quantile, 2 stops too dark.
//
// Order statistics, so that the view is robust to Monte Carlo outliers (a
// firefly moves a quantile by one rank, while it can move a mean without
// bound) and exactly invariant to the image's units: scaling every value and
// emitter_luminance by 2^k scales the result by exactly 2^-k, so the PNG is
// bit for bit the same.
AutoExposure auto_exposure(const Image& img, double emitter_luminance);

} // namespace wp
