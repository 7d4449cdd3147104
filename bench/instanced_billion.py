#!/usr/bin/env python3
"""The instancing benchmark (issue 35): a render of 10^9 instanced triangles.

Writes a scene of the Cornell room (scenes/cornell-box.json's walls and light,
millimetres) holding a shape group of one displaced sphere of 1,002,252
triangles (tools/make_displaced_sphere.py) placed by 1000 instances on a
10 x 10 x 10 grid, each turned and scaled on its own: 1,002,252,000 placed
triangles. Renders it with `wavepath render` at 256x256 and reports the
render's time, the process's peak resident memory (from the kernel's
accounting of the finished child, getrusage RUSAGE_CHILDREN), and what
`wavepath info` says the device holds.

    python3 bench/instanced_billion.py [--build build] [--spp 4] [--work DIR]
                                       [--instances-per-side 10]

Never a test: it takes about a minute here and builds a 19 MB mesh file.
"""

import argparse
import json
import math
import os
import random
import resource
import subprocess
import sys
import time


def scene(mesh_path, per_side, seed=1):
    with open(os.path.join(os.path.dirname(__file__), "..", "scenes", "cornell-box.json")) as f:
        room = json.load(f)
    # The room's walls and light: every shape but the two blocks.
    shapes = [s for s in room["shapes"] if "block" not in s.get("name", "")]
    shapes.append({"type": "shapegroup", "id": "sphere",
                   "shapes": [{"type": "mesh", "file": mesh_path, "material": "white"}]})
    rng = random.Random(seed)
    spacing = 480.0 / per_side
    radius = 0.35 * spacing
    for i in range(per_side):
        for j in range(per_side):
            for k in range(per_side):
                centre = [40 + (i + 0.5) * spacing, 20 + (j + 0.5) * spacing,
                          60 + (k + 0.5) * spacing]
                shapes.append({"type": "instance", "shapegroup": "sphere", "to_world": [
                    {"scale": [radius * rng.uniform(0.7, 1.0), radius * rng.uniform(0.7, 1.0),
                               radius * rng.uniform(0.7, 1.0)]},
                    {"rotate": {"angle": rng.uniform(0, 360),
                                "axis": [rng.uniform(-1, 1), rng.uniform(-1, 1), 1]}},
                    {"translate": centre}]})
    room["shapes"] = shapes
    room["description"] = ("bench/instanced_billion.py: %d instances of a %s" %
                           (per_side ** 3, os.path.basename(mesh_path)))
    return room


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--spp", type=int, default=4)
    parser.add_argument("--work", default="/tmp/wavepath-instanced-billion")
    parser.add_argument("--instances-per-side", type=int, default=10)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    mesh = os.path.join(args.work, "displaced-sphere.ply")
    if not os.path.exists(mesh):
        subprocess.run([sys.executable, os.path.join(root, "tools", "make_displaced_sphere.py"),
                        mesh], check=True)
    scene_path = os.path.join(args.work, "instanced-billion.json")
    with open(scene_path, "w") as f:
        json.dump(scene(mesh, args.instances_per_side), f, indent=1)
    wavepath = os.path.join(args.build, "wavepath")

    info = subprocess.run([wavepath, "info", scene_path], capture_output=True, text=True,
                          check=True).stdout
    for line in info.splitlines():
        if line.startswith(("  instances", "instances on the device", "geometry on the device",
                            "hierarchy:", "device:")):
            print("info:", line.strip())
    start = time.monotonic()
    render = subprocess.run([wavepath, "render", scene_path, "--spp", str(args.spp), "--out",
                             os.path.join(args.work, "instanced-billion.exr"), "--png",
                             os.path.join(args.work, "instanced-billion.png")],
                            capture_output=True, text=True)
    seconds = time.monotonic() - start
    sys.stdout.write(render.stdout)
    sys.stderr.write(render.stderr)
    if render.returncode != 0:
        sys.exit(render.returncode)
    # ru_maxrss of the children: the larger of info's and render's, in KiB.
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    print("render: %d spp at 256x256 in %.1f s (wall, load and build included); peak resident "
          "memory of a child %.0f MB" % (args.spp, seconds, peak / 1024.0))


if __name__ == "__main__":
    main()
