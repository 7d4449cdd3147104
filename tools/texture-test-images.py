#!/usr/bin/env python3
"""Writes the small images the texture agreement scenes read
(tests/data/mitsuba/textures/), with Mitsuba 3's Bitmap so that no other
image library is needed:

    python3 tools/texture-test-images.py tests/data/mitsuba/textures

grid.png  8x4, 8-bit sRGB: red rising left to right, green top to bottom,
          blue alternating, so that a texture turned or mirrored shows.
ramp.exr  6x5, float RGB, linear, values up to 1.
sky.exr   64x32, float RGB, an environment map (the envmap agreement scene):
          a sky bluer towards the zenith and redder towards u = 1/4 (so that
          a turned or mirrored map shows), a brown ground, and a sun of 2x2
          texels at 300 whose light outweighs the sky's.
"""
import math
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

W, H = 64, 32
sky = []
for y in range(H):
    for x in range(W):
        up = 1.0 - 2.0 * y / (H - 1)  # +1 at the zenith, -1 at the nadir
        if up > 0.0:
            warm = 0.5 + 0.5 * math.cos(2.0 * math.pi * (x + 0.5) / W - math.pi / 2.0)
            sky += [0.3 + 0.6 * warm, 0.45 + 0.2 * up, 0.6 + 0.8 * up]
        else:
            sky += [0.12, 0.08, 0.05]
        if x in (19, 20) and y in (9, 10):
            sky[-3:] = [300.0, 270.0, 220.0]
mi.Bitmap(mi.TensorXf(sky, shape=(H, W, 3)), mi.Bitmap.PixelFormat.RGB).write(out + "/sky.exr")
