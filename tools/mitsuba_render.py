#!/usr/bin/env python3
"""Renders a Mitsuba 3 scene (one written by `wavepath export-mitsuba`) with
independent seeds and prints the image's per-channel mean, and the means of
a grid of blocks, each with its standard error, for comparing against
wavepath (tests/app/test_cli_export.cpp, docs/mitsuba-export.md).

    python3 tools/mitsuba_render.py SCENE.xml [--seeds K] [--spp N] [--blocks B] [--out IMG.exr]
                                    [--error-out ERR.exr] [--variant V] [-D NAME=VALUE ...]
    python3 tools/mitsuba_render.py --images A.exr B.exr ... [--blocks B]

The second form prints the same statistics over images already rendered
with independent seeds (wavepath's, `wavepath render --seed K`), so that
both renderers' numbers come from one estimator.

Prints, channels R G B:
    mean R G B standard_error R G B                 the whole image
    block ROW COL mean R G B standard_error R G B   B x B blocks, row 0 at the top
    renders K spp N seconds T
Every mean is over pixels and renders. Its standard error comes from the K
independent renders (seeds 0..K-1): each render's mean m_k over the region
is an independent, identically distributed estimate, so the grand mean's
standard error is sd(m_k) / sqrt(K), sd the sample standard deviation
(K - 1 in the denominator). Unlike the spread of pixel values it holds no
variation of the image itself, only noise. The blocks tell images apart
that have the same mean but not the same picture (one upside down).

Uses the scalar_rgb variant by default: wavepath's colours are RGB, and it
needs no LLVM or CUDA (and no numpy). `--variant llvm_ad_rgb` renders with
LLVM instead, and evaluates the pixel filter exactly where scalar_rgb looks
it up in a 31-step table (docs/lights-and-camera.md, "the film's edge"): the
references of scenes with a tent or Gaussian filter use it.

`--out` writes the mean of the renders, and `--error-out` each pixel's standard error of that mean (from the K renders,
as above): the two images of a committed reference (tools/mitsuba-references.sh). Exit status 2 with one line on stderr when
mitsuba cannot be imported, 1 when the scene does not load.
"""
import argparse
import math
import sys
import time


def mean_and_error(estimates):
    """The mean of K independent estimates (lists of 3) and its standard error."""
    k = len(estimates)
    mean = [math.fsum(e[c] for e in estimates) / k for c in range(3)]
    variance = [math.fsum((e[c] - mean[c]) ** 2 for e in estimates) / (k - 1) for c in range(3)]
    return mean, [math.sqrt(v / k) for v in variance]


def region_means(values, width, height, channels, blocks):
    """[whole image, block (0, 0), (0, 1), ...]: the mean of each region, per channel."""
    sums = [[0.0] * 3 for _ in range(blocks * blocks)]
    counts = [0] * (blocks * blocks)
    for y in range(height):
        row = y * blocks // height
        for x in range(width):
            b = row * blocks + x * blocks // width
            p = (y * width + x) * channels
            counts[b] += 1
            for c in range(3):
                sums[b][c] += values[p + c]
    whole = [math.fsum(s[c] for s in sums) / (width * height) for c in range(3)]
    return [whole] + [[s[c] / n for c in range(3)] for s, n in zip(sums, counts)]


def channels_text(values):
    return " ".join(f"{v:.9g}" for v in values)


def print_statistics(estimates, blocks):
    mean, error = mean_and_error([e[0] for e in estimates])
    print(f"mean {channels_text(mean)} standard_error {channels_text(error)}")
    for b in range(blocks * blocks):
        mean, error = mean_and_error([e[1 + b] for e in estimates])
        print(f"block {b // blocks} {b % blocks} mean {channels_text(mean)} "
              f"standard_error {channels_text(error)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", help="Mitsuba XML scene")
    parser.add_argument("--images", nargs="+", metavar="EXR",
                        help="instead of rendering, read these independent renders")
    parser.add_argument("--seeds", type=int, default=8, help="independent renders (at least 2)")
    parser.add_argument("--spp", type=int, default=0,
                        help="samples per pixel of each render (default: the scene's sampler)")
    parser.add_argument("--blocks", type=int, default=2, help="blocks per side of the grid")
    parser.add_argument("--out", help="also write the mean image (.exr)")
    parser.add_argument("--error-out", help="also write each pixel's standard error (.exr)")
    parser.add_argument("--variant", default="scalar_rgb", choices=["scalar_rgb", "llvm_ad_rgb"],
                        help="Mitsuba variant (default scalar_rgb)")
    parser.add_argument("-D", "--define", action="append", default=[], metavar="NAME=VALUE",
                        help="set the scene's $NAME, as Mitsuba's own -D (repeatable)")
    args = parser.parse_args()
    defines = {}
    for define in args.define:
        name, equals, value = define.partition("=")
        if not equals or not name:
            parser.error(f"-D takes NAME=VALUE, got '{define}'")
        defines[name] = value
    if (args.scene is None) == (args.images is None):
        parser.error("give either a scene or --images")
    if args.images is not None and len(args.images) < 2:
        parser.error("--images needs at least 2 images (a standard error needs two renders)")
    if args.seeds < 2:
        parser.error("--seeds must be at least 2 (a standard error needs two renders)")
    if args.blocks < 1:
        parser.error("--blocks must be at least 1")
    try:
        import mitsuba as mi
    except ImportError as error:
        print(f"mitsuba_render: error: cannot import mitsuba ({error}); pip install mitsuba",
              file=sys.stderr)
        return 2
    mi.set_variant(args.variant if args.images is None else "scalar_rgb")

    if args.images is not None:
        estimates = []
        for path in args.images:
            image = mi.TensorXf(mi.Bitmap(path))
            height, width, channels = image.shape
            estimates.append(region_means(list(image.array), width, height, channels, args.blocks))
        print_statistics(estimates, args.blocks)
        print(f"images {len(args.images)}")
        return 0

    try:
        scene = mi.load_file(args.scene, **defines)
    except Exception as error:  # Mitsuba's messages span several lines
        lines = str(error).strip().splitlines()
        print(f"mitsuba_render: error: cannot load {args.scene}: "
              f"{lines[-1] if lines else error}", file=sys.stderr)
        return 1
    start = time.monotonic()
    estimates = []  # per render: the regions' means
    total = None  # the renders' images summed, value by value
    squares = None  # and their squares
    for seed in range(args.seeds):
        image = mi.render(scene, seed=seed, spp=args.spp)
        height, width, channels = image.shape
        values = list(image.array)  # row-major, row 0 at the top
        estimates.append(region_means(values, width, height, channels, args.blocks))
        total = values if total is None else [a + b for a, b in zip(total, values)]
        square = [v * v for v in values]
        squares = square if squares is None else [a + b for a, b in zip(squares, square)]
    seconds = time.monotonic() - start

    print_statistics(estimates, args.blocks)
    spp = args.spp or scene.sensors()[0].sampler().sample_count()
    print(f"renders {args.seeds} spp {spp} seconds {seconds:.3f}")
    if args.out:
        average = mi.TensorXf([v / args.seeds for v in total], shape=(height, width, channels))
        mi.Bitmap(average).write(args.out)
    if args.error_out:
        k = args.seeds
        # The sample variance of the K values, over K: the variance of their mean.
        error = [math.sqrt(max(0.0, (q - s * s / k) / (k - 1) / k)) for s, q in zip(total, squares)]
        mi.Bitmap(mi.TensorXf(error, shape=(height, width, channels))).write(args.error_out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
