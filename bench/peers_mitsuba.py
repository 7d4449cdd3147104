#!/usr/bin/env python3
"""Renders a Mitsuba 3 scene written by `wavepath export-mitsuba` with the
llvm_ad_rgb variant, for bench/peers.py (one process per render, so that
each can have its own thread count and CPU pinning):

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \
        python3 bench/peers_mitsuba.py SCENE.xml --spp 64 --seed 1 --threads 2 --out m.exr

The exported scene is the hexroom as issue #11 sets it up: analytic spheres,
`twosided` `diffuse`, `conductor` with material `none` for mirrors, an `area`
emitter of radiance 100 on a black `diffuse`, `box` filter, `path` with
`max_depth` -1 (docs/mitsuba-export.md says why each is the same as wavepath).

Prints one JSON line: render_seconds (mi.render until the image is on the
host, less Dr.Jit's kernel compilation, which, like wavepath's kernel build,
is not rendering: the first render of a kernel compiles it, about 2 s here,
later ones find it in ~/.drjit), compile_seconds, wall_seconds, threads.
Exit status 2 with one line when mitsuba or its LLVM backend is missing.
"""
import argparse
import json
import os
import sys
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--spp", type=int, required=True)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--out", required=True)
    parser.add_argument("--passes", type=int, default=1,
                        help="render this many times, seeds --seed, --seed + 1, ..., and write their mean "
                        "(a long reference without one kernel of every sample's lanes)")
    parser.add_argument("-D", "--define", action="append", default=[], metavar="NAME=VALUE",
                        help="set the scene's $NAME, as Mitsuba's own -D (repeatable)")
    args = parser.parse_args()
    defines = dict(d.partition("=")[::2] for d in args.define)
    try:
        import drjit as dr
        import mitsuba as mi
        import numpy as np
        mi.set_variant(args.variant)
    except (ImportError, AttributeError) as error:
        text = str(error).strip().splitlines()
        print(f"peers_mitsuba: error: cannot use mitsuba {args.variant} "
              f"({text[0] if text else error}); pip install mitsuba numpy, and for llvm "
              "variants set DRJIT_LIBLLVM_PATH to a libLLVM >= 16", file=sys.stderr)
        return 2
    scene = mi.load_file(args.scene, **defines)
    if args.variant.startswith("llvm"):
        # After loading: with 1 thread set before it, Mitsuba 3.9.1's parallel
        # scene loading waits forever (measured here).
        dr.set_thread_count(args.threads)
        dr.set_flag(dr.JitFlag.KernelHistory, True)
        dr.kernel_history()  # drop the loading's kernels
    start = time.monotonic()
    pixels = None
    for index in range(max(1, args.passes)):
        image = np.array(mi.render(scene, seed=args.seed + index, spp=args.spp))  # waits for the kernels
        pixels = image if pixels is None else pixels + image
    pixels = pixels / max(1, args.passes)
    wall = time.monotonic() - start
    compile_ms = 0.0
    if args.variant.startswith("llvm"):
        compile_ms = sum(k.get("backend_time", 0.0) or 0.0 for k in dr.kernel_history())
    threads = dr.thread_count() if args.variant.startswith("llvm") else 0
    if args.variant.startswith("llvm"):
        # Bitmap.write waits forever on a pool of one thread (Mitsuba 3.9.1, measured).
        dr.set_thread_count(max(2, os.cpu_count() or 2))
    mi.Bitmap(pixels).write(args.out)
    print(json.dumps({"render_seconds": wall - compile_ms / 1000.0,
                      "compile_seconds": compile_ms / 1000.0, "wall_seconds": wall,
                      "threads": threads, "variant": args.variant,
                      "mitsuba": mi.__version__}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
