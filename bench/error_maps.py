#!/usr/bin/env python3
"""Where an image's relMSE comes from: per-pixel error maps and the shape of
the error's distribution, for several renders (seeds) of one or more
renderers against one reference (docs/performance.md, "Why relMSE lags
Mitsuba's").

    python3 bench/error_maps.py --reference REF.exr --set wavepath 'wp-*.exr' \
        --set mitsuba 'mts-*.exr' [--maps DIR]

Per set (the images of one renderer, one seed each) it prints the mean MSE
and relMSE over the images (peers_image.errors: the same epsilon 0.01 for
every renderer), each image's relMSE, the median over pixels of the
per-pixel relMSE (what a typical pixel sees), the mean with the per-pixel
relMSE clipped at its 99th percentile (the image less its worst 1 %), and
the share of each image's relMSE that its 20 worst pixels carry (fireflies).
Then the shares of relMSE and MSE by the reference's brightness. With --maps
it writes, per set, the per-pixel relMSE averaged over the images as a log
false-colour PNG (1e-4 black, 5e-3 red, 0.2 yellow, 10 white), and for two or
more sets the ratio of the first set's map to each other's, in 4x4 blocks
(blue: the first set 4x lower, green: equal, red: 4x higher).
"""
import argparse
import glob
import sys
from pathlib import Path

import numpy as np

import peers_image

EPSILON = 0.01  # peers_image.errors' relMSE epsilon
BRIGHTNESS_BINS = [0.0, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, np.inf]


def relative_squared_error(image, reference):
    """Per pixel, (x - r)^2 / (r^2 + epsilon) averaged over the channels."""
    return ((image - reference) ** 2 / (reference ** 2 + EPSILON)).mean(axis=2)


def summarise(label, images, reference):
    pixel_errors = [relative_squared_error(image, reference) for image in images]
    squared = [((image - reference) ** 2).mean(axis=2) for image in images]
    relative = [float(e.mean()) for e in pixel_errors]
    worst = []
    for e in pixel_errors:
        ordered = np.sort(e.ravel())[::-1]
        worst.append(ordered[:20].sum() / ordered.sum())
    mean_map = np.mean(pixel_errors, axis=0)
    clipped = np.minimum(mean_map, np.percentile(mean_map, 99)).mean()
    print(f"| {label} | {len(images)} | {np.mean([s.mean() for s in squared]):.4f} | "
          f"{np.mean(relative):.4f} | {' '.join(f'{r:.3f}' for r in relative)} | "
          f"{np.median(mean_map):.5f} | {clipped:.4f} | {np.mean(worst):.2f} |")
    return mean_map, np.mean(squared, axis=0)


def false_colour(values, low=-4.0, high=1.0):
    x = np.clip((np.log10(values + 1e-12) - low) / (high - low), 0.0, 1.0)
    return np.stack([np.clip(3 * x, 0, 1), np.clip(3 * x - 1, 0, 1), np.clip(3 * x - 2, 0, 1)], -1)


def ratio_colour(first, other, block=4):
    h, w = first.shape
    h, w = h - h % block, w - w % block

    def blocks(m):
        return m[:h, :w].reshape(h // block, block, w // block, block).mean(axis=(1, 3))

    x = np.clip((np.log2(blocks(first) / np.maximum(blocks(other), 1e-12)) + 2.0) / 4.0, 0.0, 1.0)
    colour = np.stack([x, 1.0 - abs(x - 0.5) * 2.0, 1.0 - x], -1)
    return colour.repeat(block, 0).repeat(block, 1)


def write_png(colour, path):
    mi = peers_image._mitsuba()
    mi.Bitmap((np.clip(colour, 0, 1) * 255.0 + 0.5).astype(np.uint8)).write(str(path))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reference", required=True, help="the long render (.exr)")
    parser.add_argument("--set", nargs=2, action="append", required=True, metavar=("LABEL", "GLOB"),
                        help="a renderer's images, one per seed (a quoted glob); repeatable")
    parser.add_argument("--maps", help="write the per-pixel maps as PNGs into this folder")
    args = parser.parse_args()
    if not Path(args.reference).is_file():
        sys.exit(f"error_maps: error: reference '{args.reference}' does not exist")
    reference = peers_image.read(args.reference)
    print("| set | images | MSE | relMSE | relMSE per image | median pixel relMSE "
          "| mean, clipped at p99 | 20 worst pixels' share |")
    print("| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |")
    maps = {}
    for label, pattern in args.set:
        files = sorted(glob.glob(pattern))
        if not files:
            sys.exit(f"error_maps: error: no image matches '{pattern}'")
        images = [peers_image.read(f) for f in files]
        if any(image.shape != reference.shape for image in images):
            sys.exit(f"error_maps: error: an image of '{pattern}' is not the reference's size")
        maps[label] = summarise(label, images, reference)
    brightness = reference.mean(axis=2)
    print("\nShares of each set's relMSE (and MSE) by the reference's brightness:\n")
    print("| brightness | pixels | " + " | ".join(maps) + " |")
    print("| --- | ---: |" + " ---: |" * len(maps))
    for low, high in zip(BRIGHTNESS_BINS[:-1], BRIGHTNESS_BINS[1:]):
        inside = (brightness >= low) & (brightness < high)
        shares = [f"{r[inside].sum() / r.sum():.2f} ({s[inside].sum() / s.sum():.2f})"
                  for r, s in maps.values()]
        print(f"| [{low}, {high}) | {int(inside.sum())} | " + " | ".join(shares) + " |")
    if args.maps:
        out = Path(args.maps)
        out.mkdir(parents=True, exist_ok=True)
        labels = list(maps)
        for label in labels:
            write_png(false_colour(maps[label][0]), out / f"relmse-{label}.png")
        for label in labels[1:]:
            write_png(ratio_colour(maps[labels[0]][0], maps[label][0]),
                      out / f"ratio-{labels[0]}-over-{label}.png")


if __name__ == "__main__":
    main()
