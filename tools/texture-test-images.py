#!/usr/bin/env python3
"""Writes the small images the texture agreement scenes read
(tests/data/mitsuba/textures/), with Mitsuba 3's Bitmap so that no other
image library is needed:

    python3 tools/texture-test-images.py tests/data/mitsuba/textures

grid.png  8x4, 8-bit sRGB: red rising left to right, green top to bottom,
          blue alternating, so that a texture turned or mirrored shows.
ramp.exr  6x5, float RGB, linear, values up to 1.
"""
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")
out = sys.argv[1]

W, H = 8, 4
grid = []
for y in range(H):
    for x in range(W):
        grid += [x / (W - 1), y / (H - 1), 0.2 if (x + y) % 2 else 0.9]
bitmap = mi.Bitmap(mi.TensorXf(grid, shape=(H, W, 3)), mi.Bitmap.PixelFormat.RGB)
bitmap.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(out + "/grid.png")

W, H = 6, 5
ramp = []
for y in range(H):
    for x in range(W):
        ramp += [0.1 + 0.9 * y / (H - 1), 0.05 + 0.15 * x, 0.6 * ((x * y) % 3) / 2]
mi.Bitmap(mi.TensorXf(ramp, shape=(H, W, 3)), mi.Bitmap.PixelFormat.RGB).write(out + "/ramp.exr")
