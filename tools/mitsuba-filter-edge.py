#!/usr/bin/env python3
"""How Mitsuba 3's film weights the pixels at the image's edge, measured: an
8x8 orthographic view of an emitting rectangle whose radiance f(x) varies
across the image only (x in pixels, 0..8; a bright stripe in the outermost
quarter pixel of each side and a parabola between, symmetric about x = 4),
rendered by Mitsuba with many samples and compared, column by column, with
host models of a column's expected value computed in double precision:

  restricted exact         the filter g restricted to the image: the weighted
                           mean of f over [0, 8] with weight g(x - c), c the
                           pixel's centre (wavepath's film, kernels/camera.h)
  restricted discretized   the same with Mitsuba's table of g (31 steps over
                           the radius, each step's value taken at its inner
                           end: ReconstructionFilter::eval_discretized)
  normalised splat         each sample's weights divided by their sum over the
                           sample's whole footprint (ImageBlock's normalize)

    python3 tools/mitsuba-filter-edge.py [--variant scalar_rgb|llvm_ad_rgb]
                                         [--filter gaussian|tent] [--spp N] [--seeds K]

Prints Mitsuba's mean of each column (the two mirror columns j and 7 - j
and the 8 rows pooled) for columns 0..3 with its standard error from the K
renders, then each model's distance from it in standard errors. Keep N at
4096 or below in scalar_rgb: its film adds samples one by one in float, and
at 65536 spp per render the rounding moved the columns by several standard
errors (the same seeds at 16 x 65536 against 64 x 4096 spp). Needs Mitsuba 3
and numpy (docs/lights-and-camera.md, "The film's edge").
"""
import argparse
import math
import os
import sys
import tempfile
import time

WIDTH = 8          # the image is WIDTH x WIDTH
TEXELS = 64        # texels of the radiance texture per pixel
TABLE = 31         # Mitsuba's MI_FILTER_RESOLUTION

SCENE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="1"/></integrator>
    <sensor type="orthographic">
        <transform name="to_world"><lookat origin="0, 0, 1" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"/>
        <film type="hdrfilm">
            <integer name="width" value="{w}"/><integer name="height" value="{w}"/>
            <rfilter type="{filter}"/>
        </film>
    </sensor>
    <shape type="rectangle">
        <emitter type="area">
            <texture type="bitmap" name="radiance">
                <string name="filename" value="{texture}"/>
                <string name="filter_type" value="nearest"/>
                <boolean name="raw" value="true"/>
            </texture>
        </emitter>
    </shape>
</scene>
"""


def radiance(np, x):
    """f at film x (pixels): 10 within a quarter pixel of the left or right
    edge, else 1 + (4 - d)^2 / 4, d the distance from the nearer edge."""
    d = np.minimum(x, WIDTH - x)
    return np.where(d < 0.25, 10.0, 1.0 + 0.25 * (4.0 - d) ** 2)


def models(np, mi, filter_name, steps=1 << 22):
    """Each model's expected value of columns 0..WIDTH-1, by the midpoint
    rule over [0, WIDTH] (2^22 steps: texel edges fall on step edges)."""
    # Mitsuba's own eval (its Gaussian's exp is a Remez fit, 4e-4 from the
    # exact exp at most), tabulated finely and interpolated.
    filt = mi.load_dict({"type": filter_name})
    radius = filt.radius()
    grid = np.linspace(0.0, radius, 40001)
    values = np.array([filt.eval(float(t)) for t in grid])
    g = lambda t: np.interp(np.abs(t), grid, values, right=0.0)
    table = np.array([float(g(radius * i / TABLE)) for i in range(TABLE)] + [0.0])
    g_table = lambda t: table[np.minimum((np.abs(t) * (TABLE / radius)).astype(np.int64), TABLE)]

    x = (np.arange(steps) + 0.5) * (WIDTH / steps)
    fx = radiance(np, (np.floor(x * TEXELS) + 0.5) / TEXELS)  # the texels' values
    # A sample's footprint in ImageBlock::put: the pixel centres within the
    # radius, ceil(2 radius) of them from ceil(x - 1/2 - radius).
    first = np.ceil(x - 0.5 - radius)
    footprint = sum(g_table(first + k + 0.5 - x) for k in range(int(math.ceil(2 * radius))))
    kernels = {
        "restricted exact": lambda t: g(t),
        "restricted discretized": lambda t: g_table(t),
        "normalised splat": lambda t: g_table(t) / footprint,
    }
    out = {}
    for name, k in kernels.items():
        columns = []
        for j in range(WIDTH):
            w = k(x - (j + 0.5))
            columns.append(float(np.sum(w * fx) / np.sum(w)))
        out[name] = columns
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--variant", default="scalar_rgb", choices=["scalar_rgb", "llvm_ad_rgb"])
    parser.add_argument("--filter", default="gaussian", choices=["gaussian", "tent"])
    parser.add_argument("--spp", type=int, default=4096)
    parser.add_argument("--seeds", type=int, default=64)
    args = parser.parse_args()
    if args.seeds < 2 or args.spp < 1:
        parser.error("--seeds must be at least 2 and --spp at least 1")
    try:
        import numpy as np
        import mitsuba as mi
    except ImportError as error:
        print(f"mitsuba-filter-edge: error: {error}; pip install mitsuba numpy", file=sys.stderr)
        return 2
    mi.set_variant(args.variant)

    with tempfile.TemporaryDirectory() as folder:
        x = (np.arange(WIDTH * TEXELS) + 0.5) / TEXELS
        texture = np.repeat(radiance(np, x)[None, :, None], 3, axis=2).astype(np.float32)
        mi.Bitmap(texture).write(os.path.join(folder, "radiance.exr"))
        scene = mi.load_string(SCENE.format(w=WIDTH, filter=args.filter,
                                            texture=os.path.join(folder, "radiance.exr")))
        start = time.monotonic()
        columns = []  # per render: columns 0..3, each pooled with its mirror
        for seed in range(args.seeds):
            image = np.array(mi.render(scene, seed=seed, spp=args.spp), dtype=np.float64)[..., 0]
            c = image.mean(axis=0)
            columns.append(0.5 * (c + c[::-1])[: WIDTH // 2])
        seconds = time.monotonic() - start
    columns = np.array(columns)
    mean = columns.mean(axis=0)
    error = columns.std(axis=0, ddof=1) / math.sqrt(args.seeds)

    print(f"{args.variant} {args.filter}: {args.seeds} renders x {args.spp} spp, {seconds:.1f} s")
    print(f"{'column':24s}" + "".join(f"{j:>18d}" for j in range(WIDTH // 2)))
    print(f"{'Mitsuba':24s}" + "".join(f"{m:>10.5f} +-{e:.5f}" for m, e in zip(mean, error)))
    mi.set_variant("scalar_rgb")  # the models evaluate the filter one value at a time
    for name, values in models(np, mi, args.filter).items():
        print(f"{name:24s}" + "".join(f"{v:>10.5f} {(m - v) / e:+6.1f}s"
                                      for v, m, e in zip(values, mean, error)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
