// The page the live preview serves (preview_server.hpp): HTML, CSS and a
// little JavaScript that polls /status.json every second and reloads
// /image.png when the samples per pixel change.
#pragma once

namespace wp {

// Where the page puts the image, so that a test can find it in a screenshot
// (tests/app/test_cli_preview.cpp): its top-left corner at
// (kPreviewImageLeft, kPreviewImageTop) CSS pixels, scaled by the largest
// whole factor that fits the window less those margins on both sides (or
// shrunk to fit when even factor 1 does not), nearest-neighbour.
inline constexpr int kPreviewImageLeft = 8;
inline constexpr int kPreviewImageTop = 48;

extern const char* const kPreviewPage;

} // namespace wp
