// The filmic view's curve: ACES (the Academy Color Encoding System's
// reference rendering transform and sRGB output transform) as fitted by
// Stephen Hill for MJP's BakingLab (ACES.hlsl, 2016, public domain).
//
// Why this fit: it is ACES, the curve film and games pipelines know, in a
// few lines with no table. Hill's fit works in ACES's AP1 primaries and keeps
// the transforms' saturation matrices, so bright saturated colours turn
// towards white as ACES turns them; Narkowicz's shorter fit (2015) applies
// one curve to each sRGB channel, which drives bright colours into pure
// primaries first. AgX would need a lookup table or a polynomial fit of one,
// and a choice of look.
#pragma once

#include <array>

namespace wp {

// Linear sRGB in (exposed scene values, any non-negative range) to linear
// sRGB display values in [0, 1], before the sRGB transfer curve. Neutral in,
// neutral out; mid grey 0.18 comes out at about 0.106 (ACES's 10 % grey), and
// neutral values from about 25.7 up at 1.
std::array<double, 3> aces_filmic(const std::array<double, 3>& linear);

} // namespace wp
