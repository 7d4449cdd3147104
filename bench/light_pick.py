#!/usr/bin/env python3
"""What choosing emissive triangles by power buys (issue #31): the error of
next-event estimation that picks a triangle by power (area times luminance,
`--light-pick power`, the default) against the pick by area
(`--light-pick area`), at the same samples per pixel, on a scene whose lights
differ in power (scenes/lights/unequal-lamps.json: a dim 2 x 2 panel and a
0.2 x 0.2 lamp 1000 times brighter). Each round renders both (alternating,
seeds changing per round) and measures MSE and relMSE against one long
reference (power pick, its own seed), as `wavepath converge` defines them:
mean of (x - r)^2 and of (x - r)^2 / (r^2 + 0.01) over pixels and channels.

    python3 bench/light_pick.py [--wavepath build/wavepath] [--scene ...]
        [--size 64] [--spp 64] [--reference-spp 2048] [--rounds 3]
"""
import argparse
import os
import pathlib
import re
import statistics
import subprocess
import tempfile

import numpy as np


def read_pfm(path):
    """A PFM image as float64 rows x columns x 3, row 0 at the bottom."""
    data = pathlib.Path(path).read_bytes()
    *header, rest = data.split(b"\n", 3)
    if header[0] != b"PF":
        raise ValueError(f"{path}: not an RGB PFM")
    width, height = map(int, header[1].split())
    endian = "<" if float(header[2]) < 0 else ">"
    pixels = np.frombuffer(rest, dtype=endian + "f4", count=width * height * 3)
    return pixels.reshape(height, width, 3).astype(np.float64)


def render(wavepath, scene, size, spp, seed, pick, out):
    result = subprocess.run(
        [wavepath, "render", scene, "--width", str(size), "--height", str(size), "--spp",
         str(spp), "--seed", str(seed), "--light-pick", pick, "--out", str(out)],
        check=True, capture_output=True, text=True)
    seconds = float(re.search(r"spp, ([0-9.]+) s,", result.stdout).group(1))
    return read_pfm(out), seconds


def errors(image, reference):
    squared = (image - reference) ** 2
    return float(squared.mean()), float((squared / (reference ** 2 + 0.01)).mean())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--wavepath", default="build/wavepath")
    parser.add_argument("--scene", default="scenes/lights/unequal-lamps.json")
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--reference-spp", type=int, default=2048)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        folder = pathlib.Path(scratch)
        reference, seconds = render(args.wavepath, args.scene, args.size, args.reference_spp,
                                    1000, "power", folder / "reference.pfm")
        print(f"{args.scene}, {args.size}^2: reference {args.reference_spp} spp by power "
              f"({seconds:.2f} s); load before: {os.getloadavg()[0]:.2f}")
        rows = {"power": [], "area": []}
        for r in range(args.rounds):
            for pick in ("power", "area"):
                image, seconds = render(args.wavepath, args.scene, args.size, args.spp, r + 1,
                                        pick, folder / "image.pfm")
                mse, rel_mse = errors(image, reference)
                rows[pick].append((mse, rel_mse, seconds))
                print(f"  round {r + 1} {pick:5}: MSE {mse:.4g}, relMSE {rel_mse:.4g}, "
                      f"{seconds:.2f} s")
        mean = {pick: [statistics.fmean(x[i] for x in rows[pick]) for i in range(3)]
                for pick in rows}
        for pick in ("power", "area"):
            print(f"{pick:5} ({args.spp} spp, mean of {args.rounds}): MSE {mean[pick][0]:.4g}, "
                  f"relMSE {mean[pick][1]:.4g}, {mean[pick][2]:.2f} s")
        print(f"area / power: MSE {mean['area'][0] / mean['power'][0]:.3g}x, relMSE "
              f"{mean['area'][1] / mean['power'][1]:.3g}x, time "
              f"{mean['area'][2] / mean['power'][2]:.3g}x; load after: "
              f"{os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
