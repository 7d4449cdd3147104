#!/usr/bin/env python3
"""The film's edge, ring by ring: each image's mean over ring r (the pixels r
steps in from the nearest edge of the image) against a reference's, as a
percentage, for rings 0..3 and the inside (ring 4 on). Pixels where the
reference's largest channel exceeds 1 (a light seen directly) are left out
of every ring, in both images, and the three channels are pooled
(docs/lights-and-camera.md, "The film's edge"). Images are OpenEXR, read
by Mitsuba 3's Bitmap (pip install mitsuba), which reads both renderers'.

  tools/ring-means.py REFERENCE.exr IMAGE.exr [IMAGE.exr ...]
"""
import sys
from pathlib import Path

import numpy as np

RINGS = 4


def read_exr(path):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    try:
        return np.array(mi.TensorXf(mi.Bitmap(str(path))), dtype=np.float64)[..., :3]
    except RuntimeError as error:
        sys.exit(f"ring-means: error: cannot read {path}: {str(error).strip().splitlines()[-1]}")


def ring_means(image, keep):
    height, width, _ = image.shape
    y, x = np.mgrid[0:height, 0:width]
    ring = np.minimum(np.minimum(x, y), np.minimum(width - 1 - x, height - 1 - y))
    regions = [ring == r for r in range(RINGS)] + [ring >= RINGS]
    return [image[region & keep].mean() for region in regions]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__.strip().splitlines()[-1].strip())
    reference = read_exr(sys.argv[1])
    keep = reference.max(axis=2) <= 1.0
    expected = ring_means(reference, keep)
    print("image" + "".join(f"  ring {r}" for r in range(RINGS)) + "  inside")
    for path in sys.argv[2:]:
        image = read_exr(path)
        if image.shape != reference.shape:
            sys.exit(f"ring-means: error: {path} is {image.shape[1]}x{image.shape[0]}, "
                     f"the reference {reference.shape[1]}x{reference.shape[0]}")
        got = ring_means(image, keep)
        print(Path(path).name + "".join(f"  {100.0 * (g / e - 1.0):+.2f} %" for g, e in zip(got, expected)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
