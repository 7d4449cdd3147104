#!/usr/bin/env python3
"""Writes the Veach multiple-importance-sampling scene (Veach 1997, fig. 9.2;
docs/lights-and-camera.md): four glossy plates of rising roughness, each
tilted to reflect the lights towards the camera, under four sphere lights of
falling size and rising radiance (equal power), on a black background:

    python3 tools/veach-mis-scene.py WIDTH HEIGHT > tests/data/mitsuba/veach-mis.json

Light sampling alone is noisy on the smooth plates (a large light's cone
holds few directions the plate reflects), BSDF sampling alone on the rough
plates under the small lights (a sampled direction rarely hits them); the
power heuristic takes the better of the two everywhere.
"""
import json
import math
import sys

width, height = int(sys.argv[1]), int(sys.argv[2])
camera = (0.0, 3.0, 6.0)
target = (0.0, 0.4, 0.6)
lights = [(-1.8, 0.03), (-0.6, 0.1), (0.6, 0.3), (1.8, 0.8)]  # (x, radius)
light_y, light_z = 2.0, -1.6
alphas = [0.005, 0.02, 0.08, 0.25]


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return scale(a, 1.0 / n)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


materials, shapes = {}, []
for k, alpha in enumerate(alphas):
    # The plates from back to front, each tilted about x so that its normal
    # halves the angle between the camera and the lights' row.
    center = (0.0, 0.1 + 0.15 * k, 0.85 * k - 0.4)
    to_light = unit(sub((0.0, light_y, light_z), center))
    to_camera = unit(sub(camera, center))
    normal = unit(add(to_light, to_camera))
    along = unit(cross((1.0, 0.0, 0.0), normal))  # in the plate, across x
    half_x, half_depth = 2.4, 0.38
    corners = []
    for sx, sd in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        corners.append(add(add(center, (sx * half_x, 0.0, 0.0)), scale(along, sd * half_depth)))
    if sum(n * c for n, c in zip(normal, cross(sub(corners[1], corners[0]),
                                              sub(corners[2], corners[0])))) < 0:
        corners.reverse()
    name = "plate%d" % k
    materials[name] = {"type": "roughconductor", "material": "Al", "alpha": alpha}
    shapes.append({"name": name, "type": "quad", "material": name,
                   "vertices": [[round(v, 6) for v in c] for c in corners]})
for k, (x, radius) in enumerate(lights):
    name = "light%d" % k
    radiance = 0.8 / (radius * radius)  # equal power
    materials[name] = {"type": "emitter", "radiance": [radiance] * 3}
    shapes.append({"type": "sphere", "center": [x, light_y, light_z], "radius": radius,
                   "material": name})
scene = {
    "description": "The Veach multiple-importance-sampling scene (tools/veach-mis-scene.py): "
                   "four rough aluminium plates (GGX alpha 0.005, 0.02, 0.08, 0.25, back to front) "
                   "under four sphere lights of radius 0.03, 0.1, 0.3, 0.8 and equal power; "
                   "tests/render/test_mitsuba_agreement.cpp and docs/lights-and-camera.md.",
    "camera": {"eye": list(camera), "look_at": list(target), "up": [0, 1, 0], "fov": 45,
               "resolution": [width, height]},
    "materials": materials,
    "shapes": shapes,
}
json.dump(scene, sys.stdout, indent=1)
print()
