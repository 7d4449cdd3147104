#!/usr/bin/env python3
"""What choosing among many emitting triangles costs (issue #31: a scene with
10^4 emitting triangles must be no slower per sample than with one light,
beyond the cost of the table lookup). Two scenes with the same geometry, a
box whose ceiling is a grid of N x N quads (2 N^2 triangles), rendered
alternately with `wavepath bench`-style timing (`wavepath render`, the time
it prints):

  many: every ceiling triangle emits (next-event estimation picks one of
        2 N^2 by a search of their cumulative areas);
  one:  one ceiling quad emits as brightly as the whole ceiling did, the
        others are black (they absorb, as an emitter does: the same paths).

With --unequal the many lights' radiances differ (rows of 2, 6, 10, 14 and
18, a mean of 10), so that they are picked by power (area times luminance,
WP_HAS_POWER_LIGHT_PICK, docs/lights-and-camera.md) rather than by area.

    python3 bench/many_lights.py [--wavepath build/wavepath] [--n 71] [--size 256]
        [--spp 32] [--rounds 3] [--unequal]
"""
import argparse
import json
import pathlib
import re
import subprocess
import tempfile


LEVELS = (2, 6, 10, 14, 18)  # --unequal: the radiances of the rows, in turn


def scene(n, all_emit, unequal=False):
    materials = {
        "white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
        "red": {"type": "diffuse", "reflectance": [0.7, 0.1, 0.1]},
        "light": {"type": "emitter", "radiance": [10, 10, 10] if all_emit
                  else [10 * n * n] * 3},
        "black": {"type": "diffuse", "reflectance": [0, 0, 0]},
    }
    for k, level in enumerate(LEVELS):
        materials[f"light{k}"] = {"type": "emitter", "radiance": [level] * 3}
    box = [
        ([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], "white"),  # floor
        ([[-1, 1, 0], [1, 1, 0], [1, 1, 2], [-1, 1, 2]], "white"),  # back
        ([[-1, -1, 0], [-1, 1, 0], [-1, 1, 2], [-1, -1, 2]], "red"),  # left
        ([[1, 1, 0], [1, -1, 0], [1, -1, 2], [1, 1, 2]], "white"),  # right
    ]
    shapes = [{"type": "quad", "vertices": v, "material": m} for v, m in box]
    # The ceiling z = 2, facing down, as N x N quads.
    vertices = [[-1 + 2 * i / n, -1 + 2 * j / n, 2] for j in range(n + 1) for i in range(n + 1)]
    lit, dark = {}, []
    for j in range(n):
        for i in range(n):
            a, b = j * (n + 1) + i, j * (n + 1) + i + 1
            c, d = a + n + 1, b + n + 1
            quad = [[a, c, d], [a, d, b]]  # front face down
            material = f"light{j % len(LEVELS)}" if all_emit and unequal else "light"
            if all_emit or (i, j) == (n // 2, n // 2):
                lit.setdefault(material, []).extend(quad)
            else:
                dark.extend(quad)
    for material, triangles in lit.items():
        shapes.append({"type": "mesh", "vertices": vertices, "triangles": triangles,
                       "material": material})
    if dark:
        shapes.append({"type": "mesh", "vertices": vertices, "triangles": dark,
                       "material": "black"})
    return {"camera": {"eye": [0, -3.5, 1], "look_at": [0, 0, 1], "up": [0, 0, 1], "fov": 40,
                       "resolution": [64, 64]},
            "materials": materials, "shapes": shapes}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--wavepath", default="build/wavepath")
    parser.add_argument("--n", type=int, default=71, help="2 n^2 ceiling triangles (71: 10082)")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--spp", type=int, default=32)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--unequal", action="store_true",
                        help="the many lights' radiances differ: picked by power")
    parser.add_argument("--baseline", help="another wavepath binary (say, one built before a "
                        "change) that renders both scenes too, in the same rounds")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        folder = pathlib.Path(scratch)
        paths = {}
        for name, all_emit in (("many", True), ("one", False)):
            paths[name] = folder / f"{name}.json"
            paths[name].write_text(json.dumps(scene(args.n, all_emit, args.unequal)))
        binaries = {"": args.wavepath}
        if args.baseline:
            binaries["baseline "] = args.baseline
        rates = {}
        for _ in range(args.rounds):
            for label, binary in binaries.items():
                for name in ("many", "one"):
                    out = subprocess.run(
                        [binary, "render", str(paths[name]), "--width", str(args.size),
                         "--height", str(args.size), "--spp", str(args.spp), "--out",
                         str(folder / "out.exr")], check=True, capture_output=True, text=True)
                    rate = float(re.search(r"([0-9.e+]+) samples/s", out.stdout).group(1))
                    rates.setdefault(label + name, []).append(rate)
        print(f"{2 * args.n * args.n} emitting triangles"
              f"{' of unequal radiances' if args.unequal else ''} against 1 (of the same "
              f"{2 * args.n * args.n + 8} triangles), {args.size}^2 x {args.spp} spp, "
              f"{args.rounds} rounds alternating: samples/s")
        for label in binaries:
            for name in ("many", "one"):
                print(f"  {label}{name}: " + ", ".join(f"{r:.4g}" for r in rates[label + name]))
            ratio = [m / o for m, o in zip(rates[label + "many"], rates[label + "one"])]
            print(f"  {label}many / one, per round: " + ", ".join(f"{r:.3f}" for r in ratio))


if __name__ == "__main__":
    main()
