#!/usr/bin/env python3
"""Writes a displaced sphere as a binary little-endian PLY: the test mesh of
scenes/million.json (docs/meshes.md, "A million triangles").

The sphere is a subdivided cube pushed out onto the unit sphere (each cube face
an N x N grid of quads, two triangles each: 12 N^2 triangles, 6 N^2 + 2
vertices, shared along the cube's edges so the surface is closed). Each vertex
then moves along its direction d to the radius

    r(d) = 1 + amplitude * f(d),   f(d) in [-1, 1],

where f is a sum of plane waves sin(k * dot(u, d) + phase) with random unit
directions u, frequencies k and phases drawn from a seeded generator, weighted
1/k so the large bumps dominate. The same arguments give the same bytes.

Usage:
    python3 tools/make_displaced_sphere.py scenes/models/displaced-sphere.ply
    python3 tools/make_displaced_sphere.py OUT.ply --resolution 289 --seed 1 --amplitude 0.15

The default resolution 289 gives 1,002,252 triangles (the smallest N with
12 N^2 >= 10^6). Python 3 standard library only.
"""

import argparse
import array
import math
import os
import random
import struct
import sys
import time

WAVES = 12


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the PLY file to write (replaced atomically)")
    parser.add_argument("--resolution", type=int, default=289,
                        help="quads along each cube edge; triangles = 12 N^2 (default 289)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the waves (default 1)")
    parser.add_argument("--amplitude", type=float, default=0.15,
                        help="largest displacement, relative to the radius (default 0.15)")
    args = parser.parse_args()
    if args.resolution < 1:
        parser.error("--resolution must be at least 1")
    if not 0.0 <= args.amplitude < 1.0:
        parser.error("--amplitude must be in [0, 1) so the surface cannot pass the centre")
    return args


def make_waves(seed):
    """(unit direction, frequency, phase, weight) per wave, from the seed alone."""
    rng = random.Random(seed)
    waves = []
    for _ in range(WAVES):
        # A uniform direction: a normalised Gaussian vector.
        u = [rng.gauss(0.0, 1.0) for _ in range(3)]
        length = math.sqrt(sum(c * c for c in u))
        u = [c / length for c in u]
        frequency = rng.uniform(2.0, 24.0)
        waves.append((u, frequency, rng.uniform(0.0, 2.0 * math.pi), 1.0 / frequency))
    total = sum(w[3] for w in waves)
    # Weights summing to 1 keep |f| <= 1, so the radius stays in [1 - a, 1 + a].
    return [(u, k, phase, weight / total) for (u, k, phase, weight) in waves]


# Each cube face as (normal axis, sign, u axis, v axis) with u x v = the outward
# normal, so the quads (a, b) -> (a+1, b) -> (a+1, b+1) -> (a, b+1) run
# counter-clockwise seen from outside.
FACES = [
    (0, +1, 1, 2), (0, -1, 2, 1),
    (1, +1, 2, 0), (1, -1, 0, 2),
    (2, +1, 0, 1), (2, -1, 1, 0),
]


def build_sphere(n, waves, amplitude):
    """Positions (flat list of floats) and triangles (flat list of indices)."""
    # Cube lattice coordinate i in 0..n -> the equal-angle warp tan(pi/4 c) of
    # c = -1 + 2 i / n, which spreads the vertices more evenly over the sphere
    # than the plain cube grid. Computed once per i, so a lattice point shared by
    # two faces gets bit-identical coordinates.
    warp = [math.tan(math.pi / 4.0 * (-1.0 + 2.0 * i / n)) for i in range(n + 1)]
    index_of = {}
    positions = array.array("f")

    def vertex(lattice):
        index = index_of.get(lattice)
        if index is not None:
            return index
        x, y, z = warp[lattice[0]], warp[lattice[1]], warp[lattice[2]]
        length = math.sqrt(x * x + y * y + z * z)
        x, y, z = x / length, y / length, z / length
        f = 0.0
        for (u, k, phase, weight) in waves:
            f += weight * math.sin(k * (u[0] * x + u[1] * y + u[2] * z) + phase)
        r = 1.0 + amplitude * f
        index = len(index_of)
        index_of[lattice] = index
        positions.extend((r * x, r * y, r * z))
        return index

    triangles = array.array("i")
    for (axis, sign, u_axis, v_axis) in FACES:
        grid = []
        for b in range(n + 1):
            row = []
            for a in range(n + 1):
                lattice = [0, 0, 0]
                lattice[axis] = n if sign > 0 else 0
                lattice[u_axis] = a
                lattice[v_axis] = b
                row.append(vertex(tuple(lattice)))
            grid.append(row)
        for b in range(n):
            for a in range(n):
                p00, p10 = grid[b][a], grid[b][a + 1]
                p01, p11 = grid[b + 1][a], grid[b + 1][a + 1]
                triangles.extend((p00, p10, p11, p00, p11, p01))
    return positions, triangles


def ply_bytes(positions, triangles, comment):
    vertex_count = len(positions) // 3
    face_count = len(triangles) // 3
    header = ("ply\n"
              "format binary_little_endian 1.0\n"
              f"comment {comment}\n"
              f"element vertex {vertex_count}\n"
              "property float x\nproperty float y\nproperty float z\n"
              f"element face {face_count}\n"
              "property list uchar int vertex_indices\n"
              "end_header\n").encode("ascii")
    if sys.byteorder == "big":
        positions = array.array("f", positions)
        positions.byteswap()
    face = struct.Struct("<B3i")
    faces = bytearray(face.size * face_count)
    for t in range(face_count):
        face.pack_into(faces, face.size * t, 3, triangles[3 * t], triangles[3 * t + 1],
                       triangles[3 * t + 2])
    return header + positions.tobytes() + bytes(faces)


def main():
    args = parse_arguments()
    start = time.perf_counter()
    waves = make_waves(args.seed)
    positions, triangles = build_sphere(args.resolution, waves, args.amplitude)
    comment = (f"made by tools/make_displaced_sphere.py --resolution {args.resolution} "
               f"--seed {args.seed} --amplitude {args.amplitude!r}")
    data = ply_bytes(positions, triangles, comment)
    folder = os.path.dirname(os.path.abspath(args.out))
    os.makedirs(folder, exist_ok=True)
    # Written beside the target and renamed, so a reader never sees half a file.
    temporary = args.out + f".tmp{os.getpid()}"
    with open(temporary, "wb") as f:
        f.write(data)
    os.replace(temporary, args.out)
    seconds = time.perf_counter() - start
    print(f"{args.out}: {len(triangles) // 3} triangles, {len(positions) // 3} vertices, "
          f"{len(data)} bytes, {seconds:.1f} s")


if __name__ == "__main__":
    main()
