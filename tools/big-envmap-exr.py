#!/usr/bin/env python3
"""Writes an environment map for the stability measurements of
docs/stability.md ("Environment maps at their extremes"): a sky gradient over
a dark ground with a sun of one texel at radiance 2e6, 30 degrees up, as a
float EXR through Mitsuba's Bitmap (numpy and mitsuba from PyPI; never a
test's dependency):

    python3 tools/big-envmap-exr.py WIDTH HEIGHT OUT.exr
    python3 tools/big-envmap-exr.py 16384 8192 big.exr   # 72 MB, 12 s
"""
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
W, H, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
up = np.broadcast_to(np.linspace(1.0, -1.0, H, dtype=np.float32)[:, None], (H, W))
img = np.empty((H, W, 3), dtype=np.float32)
img[..., 0] = np.where(up > 0, 0.3 + 0.2 * up, 0.1)
img[..., 1] = np.where(up > 0, 0.5 + 0.2 * up, 0.08)
img[..., 2] = np.where(up > 0, 0.8 + 0.4 * up, 0.05)
img[int(H * 60 / 180), W // 3] = [2e6, 1.8e6, 1.5e6]
mi.Bitmap(img).write(out)
