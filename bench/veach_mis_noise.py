#!/usr/bin/env python3
"""The noise of Veach's multiple-importance-sampling scene
(tests/data/mitsuba/veach-mis.json, tools/veach-mis-scene.py) with light
sampling alone (--mis light), BSDF sampling alone (--no-nee) and both weighed
by the power heuristic (the default), per plate, against a long render with
MIS: docs/lights-and-camera.md, "Sphere lights". A benchmark (numpy and
mitsuba for the EXRs), never a test:

    python3 bench/veach_mis_noise.py [--wavepath build/wavepath] [--width 160 --height 120]
        [--spp 64] [--reference-spp 4096]

Each plate's pixels are found by rendering the scene once more with the
lights removed and each plate made an emitter of its own colour, seen
directly by camera rays: a pixel belongs to a plate where its colour is
that plate's alone.
"""
import argparse
import json
import pathlib
import subprocess
import tempfile
import time

import numpy as np

import peers_image

SCENE = pathlib.Path(__file__).resolve().parent.parent / "tests/data/mitsuba/veach-mis.json"
CODES = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 1.0)]


def render(wavepath, scene, out, width, height, spp, *flags, seed=7):
    start = time.monotonic()
    subprocess.run([wavepath, "render", str(scene), "--width", str(width), "--height",
                    str(height), "--spp", str(spp), "--sampler", "independent", "--seed", str(seed),
                    "--out", str(out), *flags], check=True, capture_output=True)
    return time.monotonic() - start, peers_image.read(out)


def plate_masks(wavepath, folder, width, height):
    scene = json.loads(SCENE.read_text())
    for k in range(4):
        scene["materials"]["plate%d" % k] = {"type": "emitter", "radiance": list(CODES[k])}
    scene["shapes"] = [s for s in scene["shapes"] if s["type"] != "sphere"]
    path = folder / "masks.json"
    path.write_text(json.dumps(scene))
    _, image = render(wavepath, path, folder / "masks.exr", width, height, 16, "--no-nee")
    return [np.all(np.abs(image - np.array(code)) < 1e-6, axis=2) for code in CODES]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--wavepath", default="build/wavepath")
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=120)
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--reference-spp", type=int, default=4096)
    parser.add_argument("--seeds", type=int, default=4,
                        help="renders per strategy, seeds 2, 3, ...: their relMSE is averaged "
                        "(one render's is dominated by its few brightest outliers)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        folder = pathlib.Path(scratch)
        masks = plate_masks(args.wavepath, folder, args.width, args.height)
        seconds, reference = render(args.wavepath, SCENE, folder / "reference.exr", args.width,
                                    args.height, args.reference_spp, seed=1)
        print(f"reference: MIS, {args.reference_spp} spp, {seconds:.1f} s; plate pixels "
              + ", ".join(str(int(m.sum())) for m in masks))
        print(f"{args.spp} spp, {args.seeds} seeds each: strategy | time a render (s, with "
              "the program build of the first) | relMSE per plate, back (alpha 0.005) to front (alpha 0.25) "
              "| whole image relMSE")
        for name, flags in (("light sampling alone", ("--mis", "light")),
                            ("BSDF sampling alone", ("--no-nee",)),
                            ("MIS (power heuristic)", ())):
            per_plate, whole, seconds = np.zeros(4), 0.0, 0.0
            for seed in range(2, 2 + args.seeds):
                took, image = render(args.wavepath, SCENE, folder / "image.exr", args.width,
                                     args.height, args.spp, *flags, seed=seed)
                seconds += took / args.seeds
                per_plate += [peers_image.errors(image[m], reference[m])[1] / args.seeds
                              for m in masks]
                whole += peers_image.errors(image, reference)[1] / args.seeds
            print(f"{name} | {seconds:.2f} | " + " ".join(f"{e:.3g}" for e in per_plate)
                  + f" | {whole:.3g}")


if __name__ == "__main__":
    main()
