#!/usr/bin/env python3
"""Writes the stress scenes of docs/stability.md into scenes/stress/.

Each scene is one case of the stability spec (specs/stability.md). Series
that are variants of the reference scene (the scale and translation series,
the tiny-light room) are derived from scenes/hexroom.json, so they follow it
if it ever changes; the others are built here from scratch.

Usage:
    python3 tools/make_stress_scenes.py            # (re)write every scene
    python3 tools/make_stress_scenes.py --check    # exit 1 if any file differs
    python3 tools/make_stress_scenes.py --out DIR  # write somewhere else

Python 3 standard library only. The output is deterministic (no randomness,
fixed key order and number formatting), so a regenerated tree diffs clean.
"""

import argparse
import copy
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEXROOM = os.path.join(ROOT, "scenes", "hexroom.json")

# Resolution written into every stress scene; tests override it as they need.
RESOLUTION = [200, 200]


def load_hexroom():
    with open(HEXROOM, encoding="utf-8") as f:
        return json.load(f)


def transform_point(p, scale, offset):
    return [scale * p[i] + offset[i] for i in range(3)]


def transformed_hexroom(scale, offset, description):
    """The hexroom with every point mapped to scale * p + offset and every
    radius multiplied by scale; radiance, reflectance and the camera's up and
    field of view unchanged, so the image is (ideally) the same."""
    scene = load_hexroom()
    scene["description"] = description
    cam = scene["camera"]
    cam["eye"] = transform_point(cam["eye"], scale, offset)
    cam["look_at"] = transform_point(cam["look_at"], scale, offset)
    cam["resolution"] = list(RESOLUTION)
    for shape in scene["shapes"]:
        if "vertices" in shape:
            shape["vertices"] = [transform_point(v, scale, offset) for v in shape["vertices"]]
        if "center" in shape:
            shape["center"] = transform_point(shape["center"], scale, offset)
        if "radius" in shape:
            shape["radius"] = scale * shape["radius"]
    return scene


def scale_series():
    out = {}
    for exponent in (-4, -2, 2, 4):
        scale = 10.0 ** exponent
        name = "scale-1e%+d" % exponent
        out[name] = transformed_hexroom(
            scale, [0.0, 0.0, 0.0],
            "Stability case 1 (scale): the hexroom with every coordinate and radius "
            "multiplied by 1e%+d, radiance unchanged. Must render like hexroom.json "
            "within noise with the same seed." % exponent)
    return out


def translation_series():
    out = {}
    for exponent in (4, 5):
        t = 10.0 ** exponent
        name = "translate-1e%d" % exponent
        out[name] = transformed_hexroom(
            1.0, [t, -t, t],
            "Stability case 2 (far from the origin): the hexroom translated by "
            "(1e%d, -1e%d, 1e%d), camera included. At 1e4 it must render like "
            "hexroom.json within noise; at 1e5 (float32 spacing 0.0078 there, "
            "about the light's 0.01 gap below the ceiling) it degrades as "
            "docs/stability.md describes, never to NaN." % (exponent, exponent, exponent))
    return out


def tiny_light_room():
    scene = load_hexroom()
    scene["description"] = (
        "Stability case 7 (tiny bright light): the hexroom with its 2 x 2 light of "
        "radiance 100 replaced by a 1e-3 x 1e-3 light of radiance 4e8 at the same "
        "centre (5, 0, 4.99): the same power (400), so the room away from the light "
        "must be lit like hexroom.json within noise.")
    scene["camera"]["resolution"] = list(RESOLUTION)
    scene["materials"]["light"]["radiance"] = [4e8, 4e8, 4e8]
    h = 0.5e-3
    for shape in scene["shapes"]:
        if shape["material"] == "light":
            shape["name"] = "tiny area light (side 1e-3, z = 4.99, faces -z)"
            shape["vertices"] = [[5 - h, -h, 4.99], [5 - h, h, 4.99], [5 + h, h, 4.99],
                                 [5 + h, -h, 4.99]]
    return {"tiny-light": scene}


# ---------------------------------------------------------------- helpers

def camera(eye, look_at, up, fov, resolution=None):
    return {"eye": eye, "look_at": look_at, "up": up, "fov": fov,
            "resolution": list(resolution or RESOLUTION)}


def quad(name, material, a, b, c, d):
    return {"name": name, "type": "quad", "material": material, "vertices": [a, b, c, d]}


def box_inward(name, material, lo, hi):
    """The six faces of the box [lo, hi] as one 12-triangle mesh, front faces
    inwards; every edge is shared by exactly two triangles (closed)."""
    v = [[hi[0] if (i & 1) else lo[0], hi[1] if (i & 2) else lo[1],
          hi[2] if (i & 4) else lo[2]] for i in range(8)]
    # Outward winding per face, then flipped to face inwards.
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = []
    for a, b, c, d in faces:
        tris += [[a, c, b], [a, d, c]]
    return {"name": name, "type": "mesh", "material": material, "vertices": v,
            "triangles": tris}


def icosphere(subdivisions):
    """Unit icosphere: vertices on the unit sphere, triangles wound outwards."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    verts = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
             [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    verts = [[c / math.sqrt(sum(x * x for x in v)) for c in v] for v in verts]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
             [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
             [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    for _ in range(subdivisions):
        cache = {}

        def midpoint(i, j):
            key = (min(i, j), max(i, j))
            if key not in cache:
                m = [(verts[i][k] + verts[j][k]) / 2.0 for k in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append([x / n for x in m])
                cache[key] = len(verts) - 1
            return cache[key]

        new_faces = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            new_faces += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = new_faces
    return verts, faces


# ---------------------------------------------------------------- the cases

def closed_meshes():
    out = {}
    # Icosphere of radius 1.3 around a centre with no round coordinates,
    # triangles flipped to face inwards, an emitter: every camera ray must
    # see exactly its radiance.
    centre, radius = [0.37, -0.21, 0.13], 1.3
    verts, faces = icosphere(1)
    out["closed-icosphere"] = {
        "description": "Stability case 3 (shared edges and vertices): camera inside a closed "
                       "icosphere (80 triangles, radius 1.3, inward-facing emitter of radiance "
                       "1). Every ray from inside must hit it, including rays aimed exactly "
                       "at its edges and vertices; every pixel reads exactly 1.",
        "camera": camera([0.37 + 0.1, -0.21 - 0.05, 0.13 + 0.02], [1.37, 0.3, 0.4],
                         [0, 0, 1], 120),
        "materials": {"inside": {"type": "emitter", "radiance": [1, 1, 1]}},
        "shapes": [{"name": "icosphere, faces inward", "type": "mesh", "material": "inside",
                    "vertices": [[centre[k] + radius * v[k] for k in range(3)] for v in verts],
                    "triangles": [[a, c, b] for a, b, c in faces]}],
    }
    out["closed-cube"] = {
        "description": "Stability case 3 (shared edges and vertices): camera at the centre of "
                       "the closed cube [-1, 1]^3 (12 triangles, inward-facing emitter of "
                       "radiance 1), looking at a corner where six triangles meet. Every "
                       "pixel reads exactly 1.",
        "camera": camera([0, 0, 0], [1, 1, 1], [0, 0, 1], 120),
        "materials": {"inside": {"type": "emitter", "radiance": [1, 1, 1]}},
        "shapes": [box_inward("cube, faces inward", "inside", [-1, -1, -1], [1, 1, 1])],
    }
    return out


def contact():
    # A diffuse sphere resting on the floor (touching it at one point) and a
    # regular tetrahedron whose base lies in the floor plane, lit from above;
    # the camera looks down at the contact point and the base edge.
    s = math.sqrt(3.0)
    a = 1.0  # tetrahedron side
    base = [[2.0, -0.5 * a, 0.0], [2.0, 0.5 * a, 0.0], [2.0 + s / 2 * a, 0.0, 0.0]]
    apex = [2.0 + s / 6 * a, 0.0, math.sqrt(2.0 / 3.0) * a]
    return {"contact": {
        "description": "Stability case 4 (contact): a diffuse sphere of radius 1 resting on a "
                       "diffuse floor (touching at (0, 0, 0)) and a regular tetrahedron of "
                       "side 1 whose base lies in the floor plane z = 0, under a 1 x 1 "
                       "light at z = 4. The floor next to the contact point must be dark, "
                       "with no bright seam along the tetrahedron's base.",
        "camera": camera([-2.5, -3.0, 2.5], [0.6, 0.0, 0.0], [0, 0, 1], 50),
        "materials": {
            "floor": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
            "ball": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
            "tetra": {"type": "diffuse", "reflectance": [0.6, 0.3, 0.48]},
            "light": {"type": "emitter", "radiance": [40, 40, 40]},
        },
        "shapes": [
            quad("floor z = 0, faces +z", "floor", [-6, -6, 0], [6, -6, 0], [6, 6, 0],
                 [-6, 6, 0]),
            {"name": "sphere touching the floor at the origin", "type": "sphere",
             "material": "ball", "center": [0, 0, 1], "radius": 1},
            {"name": "tetrahedron, base in the floor plane, faces outward", "type": "mesh",
             "material": "tetra", "vertices": base + [apex],
             "triangles": [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]]},
            quad("light z = 4, faces -z", "light", [-0.5, -0.5, 4], [-0.5, 0.5, 4],
                 [0.5, 0.5, 4], [0.5, -0.5, 4]),
        ],
    }}


def mirror_corridor():
    return {"mirror-corridor": {
        "description": "Stability case 5 (mirror corridor): two parallel lossless mirrors "
                       "(4 x 4, at x = -1 and x = 1, facing each other), the camera between "
                       "them looking at one mirror head-on, and off the axis a light closing "
                       "the corridor's +y side. A ray with lateral slopes (ty, tz) "
                       "bounces until it leaves the corridor through the side of its larger "
                       "slope, so the image is exact: radiance 10 where ty > |tz|, else 0. "
                       "Rays near the axis bounce thousands of times; the depth cap must cut "
                       "and count them and the render must end.",
        "camera": camera([0, 0, 0], [1, 0, 0], [0, 0, 1], 20),
        "materials": {
            "mirror": {"type": "mirror", "reflectance": [1, 1, 1]},
            "light": {"type": "emitter", "radiance": [10, 10, 10]},
        },
        "shapes": [
            quad("mirror x = 1, faces -x", "mirror", [1, -2, -2], [1, -2, 2], [1, 2, 2],
                 [1, 2, -2]),
            quad("mirror x = -1, faces +x", "mirror", [-1, -2, -2], [-1, 2, -2], [-1, 2, 2],
                 [-1, -2, 2]),
            quad("light closing the corridor's +y side (y = 2), faces -y", "light",
                 [-1, 2, -2], [1, 2, -2], [1, 2, 2], [-1, 2, 2]),
        ],
    }}


def light_near_surface():
    return {"light-near-surface": {
        "description": "Stability case 6 (light almost touching a surface): a 1 x 1 light of "
                       "radiance 10 facing down, 1e-3 above a large diffuse floor. "
                       "Next-event estimation's 1/d^2 reaches 1e6 at the floor: no Inf or "
                       "NaN, and the error must keep falling with samples.",
        "camera": camera([0, -2.5, 2.0], [0, 0, 0], [0, 0, 1], 60),
        "materials": {
            "floor": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
            "light": {"type": "emitter", "radiance": [10, 10, 10]},
        },
        "shapes": [
            quad("floor z = 0, faces +z", "floor", [-20, -20, 0], [20, -20, 0], [20, 20, 0],
                 [-20, 20, 0]),
            quad("light z = 1e-3, faces -z", "light", [-0.5, -0.5, 1e-3], [-0.5, 0.5, 1e-3],
                 [0.5, 0.5, 1e-3], [0.5, -0.5, 1e-3]),
        ],
    }}


def furnace():
    return {"furnace-099": {
        "description": "Stability case 8 (near-white furnace): a closed box whose walls are "
                       "all diffuse with albedo 0.99 and emit 1: every pixel converges to "
                       "Le / (1 - 0.99) = 100.",
        "camera": camera([0.2, -0.1, 0.3], [1, 0.3, 0.1], [0, 0, 1], 100),
        "materials": {"wall": {"type": "diffuse", "reflectance": [0.99, 0.99, 0.99],
                               "emission": [1, 1, 1]}},
        "shapes": [box_inward("box [-1, 1]^3, faces inward", "wall", [-1, -1, -1], [1, 1, 1])],
    }}


def spheres():
    return {
        "sphere-far-small": {
            "description": "Stability case 9 (sphere precision): a sphere of radius 1e-3 at "
                           "distance 1e3 from the camera, which looks at it with a 2e-4 "
                           "degree field of view (the sphere fills the middle of the image). "
                           "The textbook quadratic loses it entirely.",
            "camera": camera([0, 0, 0], [1000, 0, 0], [0, 0, 1], 2e-4),
            "materials": {"white": {"type": "diffuse", "reflectance": [0.8, 0.8, 0.8]},
                          "light": {"type": "emitter", "radiance": [5, 5, 5]}},
            "shapes": [
                {"name": "small far sphere", "type": "sphere", "material": "white",
                 "center": [1000, 0, 0], "radius": 1e-3},
                quad("light behind the camera, faces +x", "light", [-1, -1, -1], [-1, 1, -1],
                     [-1, 1, 1], [-1, -1, 1]),
            ],
        },
        "sphere-ground": {
            "description": "Stability case 9 (sphere precision): a sphere of radius 1e4 as the "
                           "ground (top at z = 0), the camera 1.7 above it looking at the "
                           "horizon, a light overhead.",
            "camera": camera([0.3, -0.2, 1.7], [10.3, 0.5, 0.2], [0, 0, 1], 70),
            "materials": {"ground": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
                          "light": {"type": "emitter", "radiance": [20, 20, 20]}},
            "shapes": [
                {"name": "ground sphere", "type": "sphere", "material": "ground",
                 "center": [0, 0, -10000], "radius": 10000},
                quad("light z = 10, faces -z", "light", [0, -5, 10], [0, 5, 10], [10, 5, 10],
                     [10, -5, 10]),
            ],
        },
    }


def grazing():
    # A tilted triangle (no axis-aligned coordinates) seen edge-on: the camera
    # sits in the triangle's plane, so camera rays graze it within fractions
    # of a microradian. The adversarial rays of the tests use the same triangle.
    v0, v1, v2 = [0.3, -1.1, 0.2], [2.9, 0.4, 0.9], [1.1, 1.7, -0.6]
    e1 = [v1[k] - v0[k] for k in range(3)]
    e2 = [v2[k] - v0[k] for k in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
         e1[0] * e2[1] - e1[1] * e2[0]]
    centroid = [(v0[k] + v1[k] + v2[k]) / 3 for k in range(3)]
    # Eye: back from the centroid along the plane direction (v0 + v2)/2 - v1.
    d = [(v0[k] + v2[k]) / 2 - v1[k] for k in range(3)]
    eye = [centroid[k] + 2.0 * d[k] for k in range(3)]
    return {"grazing": {
        "description": "Stability case 10 (grazing rays): a tilted triangle seen edge-on from "
                       "a camera in its own plane, lit from above. The tests' adversarial rays "
                       "use the same triangle. Rays within 1e-6 rad of the plane must never hit outside the "
                       "triangle.",
        "camera": camera(eye, centroid, n, 10),
        "materials": {"white": {"type": "diffuse", "reflectance": [0.8, 0.8, 0.8]},
                      "light": {"type": "emitter", "radiance": [5, 5, 5]}},
        "shapes": [
            {"name": "tilted triangle", "type": "triangle", "material": "white",
             "vertices": [v0, v1, v2]},
            quad("light above, faces -z", "light", [-5, -5, 8], [-5, 5, 8], [5, 5, 8],
                 [5, -5, 8]),
        ],
    }}


def degenerate():
    """Case 11: one file per kind of bad input. The zero-area triangle loads
    (skipped with a warning); every other file must fail with a message naming
    its field (the expected pointer is in the description)."""
    base_cam = camera([0, 0, 3], [0, 0, 0], [0, 1, 0], 60)
    mats = {"white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
            "light": {"type": "emitter", "radiance": [10, 10, 10]}}
    good = [quad("floor", "white", [-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]),
            quad("light", "light", [-1, -1, 2], [-1, 1, 2], [1, 1, 2], [1, -1, 2])]

    def scene(description, cam=None, materials=None, shapes=None):
        return {"description": description, "camera": cam or copy.deepcopy(base_cam),
                "materials": materials or copy.deepcopy(mats),
                "shapes": shapes if shapes is not None else copy.deepcopy(good)}

    out = {}
    out["degenerate-zero-area"] = scene(
        "Stability case 11: a zero-area triangle (three collinear corners) next to good "
        "shapes: loads with the warning '/shapes/2: skipped zero-area triangle'.",
        shapes=copy.deepcopy(good) + [{"name": "collinear", "type": "triangle",
                                       "material": "white",
                                       "vertices": [[0, 0, 1], [1, 1, 1], [2, 2, 1]]}])
    out["degenerate-inf-coordinate"] = scene(
        "Stability case 11: an infinite coordinate (1e999 overflows a double): error at "
        "/shapes/0/vertices/1/0.")
    out["degenerate-inf-coordinate"]["shapes"][0]["vertices"][1][0] = "INF_PLACEHOLDER"
    out["degenerate-huge-coordinate"] = scene(
        "Stability case 11: a coordinate beyond float32's safe range (|x| > 1e30): error "
        "at /shapes/0/vertices/2/1.")
    out["degenerate-huge-coordinate"]["shapes"][0]["vertices"][2][1] = 3e30
    out["degenerate-negative-radius"] = scene(
        "Stability case 11: a sphere of negative radius: error at /shapes/2/radius.",
        shapes=copy.deepcopy(good) + [{"type": "sphere", "material": "white",
                                       "center": [0, 0, 1], "radius": -0.5}])
    out["degenerate-zero-resolution"] = scene(
        "Stability case 11: a zero image width: error at /camera/resolution/0.")
    out["degenerate-zero-resolution"]["camera"]["resolution"] = [0, 200]
    out["degenerate-up-parallel"] = scene(
        "Stability case 11: up parallel to the view direction: error at /camera/up.")
    out["degenerate-up-parallel"]["camera"]["up"] = [0, 0, 2]
    out["degenerate-huge-radiance"] = scene(
        "Stability case 11: radiance over 1e30: error at /materials/light/radiance/1.")
    out["degenerate-huge-radiance"]["materials"]["light"]["radiance"] = [10, 2e30, 10]
    return out


def emitters():
    return {"emitter-faces": {
        "description": "Stability case 12 (emitter back faces and grazing views): a 2 x 2 "
                       "light of radiance 10 facing +z seen from a camera almost in its "
                       "plane (0.05 above it, 6 away: about 0.5 degrees), a second one seen "
                       "from behind (from below), both in front of an emitting backdrop of "
                       "radiance 1, and a diffuse wall standing on the first light's edge, "
                       "which sees it at grazing angles. Back faces are black (exactly 0), "
                       "the grazing front face reads exactly 10, and every value is finite.",
        "camera": camera([-6, 0, 0.05], [0, 0, 0], [0, 0, 1], 40),
        "materials": {"wall": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
                      "light": {"type": "emitter", "radiance": [10, 10, 10]},
                      "backdrop": {"type": "emitter", "radiance": [1, 1, 1]}},
        "shapes": [
            quad("light z = 0 facing +z (front seen at grazing)", "light", [-1, -1, 0],
                 [1, -1, 0], [1, 1, 0], [-1, 1, 0]),
            quad("light z = 1 facing +z (its back seen from below)", "light",
                 [-1, 0.5, 1], [1, 0.5, 1], [1, 2.5, 1], [-1, 2.5, 1]),
            quad("wall x = 1 on the first light's edge, faces -x", "wall", [1, -1, 0],
                 [1, -1, 1.5], [1, 1, 1.5], [1, 1, 0]),
            quad("backdrop x = 20, faces -x", "backdrop", [20, -30, -30], [20, -30, 30],
                 [20, 30, 30], [20, 30, -30]),
        ],
    }}


def all_scenes():
    scenes = {}
    for part in (scale_series, translation_series, closed_meshes, contact, mirror_corridor,
                 light_near_surface, tiny_light_room, furnace, spheres, grazing, degenerate,
                 emitters):
        scenes.update(part())
    return scenes


def render_json(value, indent=0):
    """JSON with objects one key per line and arrays of numbers (points,
    colours) on one line, like scenes/hexroom.json."""
    pad = "  " * indent
    if isinstance(value, dict):
        items = ["%s  %s: %s" % (pad, json.dumps(k), render_json(v, indent + 1))
                 for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if all(not isinstance(v, (dict, list)) for v in value):
            return "[" + ", ".join(render_json(v) for v in value) + "]"
        items = [pad + "  " + render_json(v, indent + 1) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    if value == "INF_PLACEHOLDER":
        # JSON has no infinity: 1e999 is how a file writes one (it overflows
        # a double when read), which is what the degenerate case needs.
        return "1e999"
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError("JSON cannot hold %r" % value)
        return repr(value)
    return json.dumps(value)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join(ROOT, "scenes", "stress"))
    parser.add_argument("--check", action="store_true",
                        help="compare with the files on disk instead of writing")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    stale = []
    for name, scene in sorted(all_scenes().items()):
        path = os.path.join(args.out, name + ".json")
        text = render_json(scene) + "\n"
        if args.check:
            try:
                with open(path, encoding="utf-8") as f:
                    if f.read() != text:
                        stale.append(path)
            except OSError:
                stale.append(path)
        else:
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
    if stale:
        print("out of date: " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
