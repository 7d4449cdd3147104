#!/usr/bin/env python3
"""Where the bounding volume hierarchy starts to beat testing every primitive.

Writes the hexroom with small random triangles floating in it (n triangles in
all, as docs/specialization.md's clutter scenes) to a temporary folder and
times the intersect and shadow stages alone (`wavepath bench`, 2^20 random
rays) with `--traversal loop` and `--traversal bvh`, alternating, best of
`--rounds`. Prints a markdown table. Standard library only.

    python3 tools/bvh_threshold.py [--wavepath build/wavepath] [--rounds 3]
"""
import argparse
import json
import os
import random
import re
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def clutter_scene(n, folder):
    with open(os.path.join(ROOT, "scenes", "hexroom.json")) as f:
        s = json.load(f)
    rng = random.Random(n)
    s["materials"]["clutter"] = {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}
    tris = []
    for _ in range(n - 26):
        c = [rng.uniform(0, 10), rng.uniform(-4, 4), rng.uniform(-4.5, 3.5)]
        tris.append([[c[k] + rng.uniform(-0.3, 0.3) for k in range(3)] for _ in range(3)])
    if tris:
        s["shapes"].append({"type": "mesh", "material": "clutter",
                            "vertices": [v for t in tris for v in t],
                            "triangles": [[3 * i, 3 * i + 1, 3 * i + 2] for i in range(len(tris))]})
    path = os.path.join(folder, "hexroom-%d.json" % n)
    with open(path, "w") as f:
        json.dump(s, f)
    return path


def stage_rates(wavepath, scene, traversal):
    out = subprocess.run([wavepath, "bench", scene, "--size", "16", "--spp", "1",
                          "--repetitions", "3", "--traversal", traversal],
                         check=True, capture_output=True, text=True).stdout
    rates = re.findall(r"\((closest|any) hit\):\s+([0-9.]+) Mrays/s", out)
    return {kind: float(rate) for kind, rate in rates}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--wavepath", default=os.path.join(ROOT, "build", "wavepath"))
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--sizes", default="30,60,100,128,200,300,1000,3000")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        print("| triangles | intersect loop | intersect bvh | shadow loop | shadow bvh |")
        print("| --- | --- | --- | --- | --- |")
        for n in (int(x) for x in args.sizes.split(",")):
            scene = clutter_scene(n, folder)
            best = {}
            for _ in range(args.rounds):
                for traversal in ("loop", "bvh"):
                    for kind, rate in stage_rates(args.wavepath, scene, traversal).items():
                        key = (traversal, kind)
                        best[key] = max(best.get(key, 0.0), rate)
            print("| %d + 2 spheres | %.2f | %.2f | %.2f | %.2f |" % (
                n, best[("loop", "closest")], best[("bvh", "closest")],
                best[("loop", "any")], best[("bvh", "any")]), flush=True)


if __name__ == "__main__":
    main()
