#!/usr/bin/env python3
"""Mitsuba 3's roughplastic measured through its own Python API (the facts
that tests/scene/test_material_table.cpp and tests/kernels/test_bsdf.cpp fix,
docs/materials.md):

    python3 tools/mitsuba_roughplastic.py tables          # R_int and T(mu)
    python3 tools/mitsuba_roughplastic.py albedo [N]      # white furnace
    python3 tools/mitsuba_roughplastic.py cases OUT.json  # eval and pdf at direction pairs

`tables`: with specular_reflectance 0 the BSDF is its base alone,
eval(mu, mu) = rho' T(mu)^2 mu / (pi eta^2), rho' = rho / (1 - rho R_int) when
nonlinear; R_int follows from two diffuse reflectances (0.5 and 1), then T at
the table's cosines i / 63. `albedo`: the mean of N sample() weights (default
400000) for a white base under a clear coating, with its standard error.
Needs `pip install mitsuba` (3.9.1 made the committed numbers), scalar_rgb.
"""
import json
import math
import random
import sys

import mitsuba as mi

mi.set_variant('scalar_rgb')


def bsdf(dist, alpha, int_ior, diffuse, nonlinear, specular=None):
    d = {'type': 'roughplastic', 'distribution': dist, 'alpha': alpha, 'int_ior': int_ior,
         'diffuse_reflectance': {'type': 'rgb', 'value': diffuse}, 'nonlinear': nonlinear}
    if specular is not None:
        d['specular_reflectance'] = {'type': 'rgb', 'value': specular}
    return mi.load_dict(d)


def interaction(wi):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wi)
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    return si


def evaluate(b, wi, wo):
    ctx, si = mi.BSDFContext(), interaction(wi)
    v = b.eval(ctx, si, mi.Vector3f(*wo))
    return [float(v[0]), float(v[1]), float(v[2])], float(b.pdf(ctx, si, mi.Vector3f(*wo)))


def at(mu):
    return (math.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu)


def tables():
    for dist, alpha, ior in [('ggx', 0.1, 1.49), ('beckmann', 0.3, 1.49), ('ggx', 0.7, 2.4),
                             ('beckmann', 0.05, 0.8)]:
        eta = ior / 1.000277
        half, white = (bsdf(dist, alpha, ior, d, True, 0.0) for d in (0.5, 1.0))
        r = evaluate(white, at(0.7), at(0.6))[0][0] / evaluate(half, at(0.7), at(0.6))[0][0]
        r_int = (r - 2.0) / (r - 1.0)  # r = 2 (1 - R/2) / (1 - R)
        t = []
        for i in (1, 16, 40, 63):
            mu = i / 63
            e = evaluate(white, at(mu), at(mu))[0][0]
            t.append(math.sqrt(max(0.0, e * math.pi * eta * eta * (1.0 - r_int) / mu)))
        print(f'{dist} alpha {alpha} int_ior {ior}: R_int {r_int:.6f} T(1/63, 16/63, 40/63, 1) '
              + ' '.join(f'{x:.6f}' for x in t))


def albedo(n):
    random.seed(7)
    for dist, alpha, nonlinear in [('ggx', 0.1, False), ('beckmann', 0.2, True)]:
        b = bsdf(dist, alpha, 1.49, 1.0, nonlinear)
        for degrees in (0, 45, 75):
            theta = math.radians(degrees)
            ctx, si = mi.BSDFContext(), interaction((math.sin(theta), 0.0, math.cos(theta)))
            s = s2 = 0.0
            for _ in range(n):
                _, w = b.sample(ctx, si, random.random(),
                                mi.Point2f(random.random(), random.random()))
                s += float(w[0])
                s2 += float(w[0]) ** 2
            m = s / n
            print(f'{dist} alpha {alpha} nonlinear {nonlinear} incidence {degrees}: '
                  f'albedo {m:.5f} +- {math.sqrt(max(0.0, s2 / n - m * m) / n):.5f}')


def cases(out):
    random.seed(1)
    result = []
    for dist in ('ggx', 'beckmann'):
        for alpha, ior, diffuse, specular, nonlinear in [
                (0.1, 1.49, [0.2, 0.5, 0.8], None, False),
                (0.4, 1.7, [0.9, 0.3, 0.1], [0.8, 0.6, 1.0], True),
                (0.02, 1.33, [0.5, 0.5, 0.5], None, False)]:
            b = bsdf(dist, alpha, ior, diffuse, nonlinear, specular)
            for k in range(40):
                c, phi = random.uniform(0.02, 1.0), random.uniform(0.0, 2.0 * math.pi)
                s = math.sqrt(1.0 - c * c)
                wi = (s * math.cos(phi), s * math.sin(phi), c)
                if k % 2 == 0:  # near the mirror direction, where the coating shows
                    wo = (-wi[0] + random.gauss(0, alpha), -wi[1] + random.gauss(0, alpha), wi[2])
                    length = math.sqrt(sum(x * x for x in wo))
                    wo = tuple(x / length for x in wo)
                else:
                    c2, p2 = random.uniform(0.02, 1.0), random.uniform(0.0, 2.0 * math.pi)
                    s2 = math.sqrt(1.0 - c2 * c2)
                    wo = (s2 * math.cos(p2), s2 * math.sin(p2), c2)
                e, p = evaluate(b, wi, wo)
                result.append({'distribution': dist, 'alpha': alpha, 'int_ior': ior,
                               'diffuse': diffuse, 'specular': specular,
                               'nonlinear': nonlinear, 'wi': wi, 'wo': wo, 'eval': e, 'pdf': p})
    json.dump(result, open(out, 'w'), indent=0)
    print(f'{len(result)} direction pairs written to {out}')


if __name__ == '__main__':
    command = sys.argv[1] if len(sys.argv) > 1 else ''
    if command == 'tables':
        tables()
    elif command == 'albedo':
        albedo(int(sys.argv[2]) if len(sys.argv) > 2 else 400000)
    elif command == 'cases' and len(sys.argv) > 2:
        cases(sys.argv[2])
    else:
        sys.exit(__doc__)
