#!/usr/bin/env python3
"""Mitsuba 3's cuda_ad_rgb on a scene written by `wavepath export-mitsuba`,
timed the way wavepath's renders are: the first render compiles Dr.Jit's
kernels (like wavepath's program build, not rendering), the later ones are
timed, each from mi.render until the image is on the host. For the device
kit (tools/device/run.sh, docs/gpu.md):

    python3 mitsuba_gpu.py SCENE.xml --spp 64 --repeats 5 --out m64.exr \
        [--reference-spp 1024 --reference-out m1024.exr]

Prints one JSON line per timed render and one summary line (median seconds,
samples/s). Exit status 2 with one line on stderr when mitsuba, its CUDA
backend or OptiX is missing, so that the kit says why and goes on.
"""
import argparse
import json
import statistics
import sys
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", required=True)
    parser.add_argument("--reference-spp", type=int, default=0)
    parser.add_argument("--reference-out")
    parser.add_argument("--variant", default="cuda_ad_rgb",
                        help="scalar_rgb to practise on a machine without a GPU")
    args = parser.parse_args()
    try:
        import drjit as dr
        import mitsuba as mi
        import numpy as np
        mi.set_variant(args.variant)
        scene = mi.load_file(args.scene)
    except Exception as error:  # ImportError, or no CUDA driver / OptiX
        lines = [line for line in str(error).strip().splitlines() if line.strip()]
        print(f"mitsuba_gpu: error: cannot render with {args.variant}: "
              f"{lines[-1] if lines else type(error).__name__}", file=sys.stderr)
        return 2
    film = scene.sensors()[0].film()
    width, height = film.size()

    def timed_render(spp, seed):
        start = time.monotonic()
        image = mi.render(scene, seed=seed, spp=spp)
        pixels = np.array(image)  # waits for the kernels
        if args.variant.startswith("cuda"):
            dr.sync_thread()
        return time.monotonic() - start, pixels

    compile_seconds, _ = timed_render(args.spp, 1000)
    print(json.dumps({"first_render_seconds": compile_seconds, "spp": args.spp}), flush=True)
    times = []
    pixels = None
    for seed in range(args.repeats):
        seconds, pixels = timed_render(args.spp, seed)
        times.append(seconds)
        print(json.dumps({"seed": seed, "seconds": seconds}), flush=True)
    mi.Bitmap(pixels).write(args.out)
    median = statistics.median(times)
    summary = {"variant": args.variant, "mitsuba": mi.__version__, "width": width,
               "height": height, "spp": args.spp, "median_seconds": median,
               "samples_per_second": width * height * args.spp / median}
    if args.reference_spp and args.reference_out:
        seconds, reference = timed_render(args.reference_spp, 7777)
        mi.Bitmap(reference).write(args.reference_out)
        summary["reference_spp"] = args.reference_spp
        summary["reference_seconds"] = seconds
    print(json.dumps(summary), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
