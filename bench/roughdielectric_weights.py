"""The weights of the rough dielectric's samples, by how it picks its side
(docs/performance.md, "The frosted sphere's speckle"): a numpy model of
kernels/bsdf/roughdielectric.h's sampler, GGX visible normals (Heitz 2018)
and the dielectric Fresnel term, in double precision.

  python3 bench/roughdielectric_weights.py [--alpha 0.2] [--ior 1.5046] [--samples 400000]

For light arriving from outside and from inside the glass at several
incidence cosines v.z it prints the mean, second moment and largest weight
(f cos / pdf, with the (n_from / n_to)^2 of transmission) of

  old: the side first, reflection with P = F(v.z) kept within [0.05, 0.95],
       the normal from the rest of the number (wavepath before 2026-12-07);
  new: the normal first, the side by F(v.h) from a third number (Mitsuba 3).

Both means are the same (both unbiased); the second moment is the variance a
path carries away from the surface. A model, not a test: the kernels' own
sampler is tested in tests/kernels/test_bsdf.cpp."""
import argparse

import numpy as np


def fresnel(cos_i, eta):
    """Unpolarised reflectance and the refracted cosine (1 and 0 past the critical angle)."""
    cos_i = np.clip(cos_i, 0.0, 1.0)
    cos_t2 = 1.0 - (1.0 - cos_i ** 2) / eta ** 2
    cos_t = np.sqrt(np.maximum(cos_t2, 0.0))
    a_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    a_p = (cos_t - eta * cos_i) / (cos_t + eta * cos_i)
    return np.where(cos_t2 > 0.0, np.clip(0.5 * (a_s ** 2 + a_p ** 2), 0.0, 1.0), 1.0), cos_t


def smith_g1(alpha, w, m):
    tan2 = alpha ** 2 * (w[..., 0] ** 2 + w[..., 1] ** 2) / w[..., 2] ** 2
    seen = np.sum(w * m, axis=-1) * w[..., 2] > 0.0
    return np.where(seen, 2.0 / (1.0 + np.sqrt(1.0 + tan2)), 0.0)


def sample_visible(alpha, v, u1, u2):
    """GGX normals visible from v (Heitz 2018), as kernels/bsdf/microfacet.h."""
    s = np.array([alpha * v[0], alpha * v[1], v[2]])
    s /= np.linalg.norm(s)
    lensq = s[0] ** 2 + s[1] ** 2
    t1 = np.array([-s[1], s[0], 0.0]) / np.sqrt(lensq) if lensq > 0.0 else np.array([1.0, 0.0, 0.0])
    t2 = np.cross(s, t1)
    r, phi = np.sqrt(u1), 2.0 * np.pi * u2
    p1, p2 = r * np.cos(phi), r * np.sin(phi)
    half = 0.5 * (1.0 + s[2])
    p2 = (1.0 - half) * np.sqrt(np.maximum(0.0, 1.0 - p1 * p1)) + half * p2
    nh = p1[:, None] * t1 + p2[:, None] * t2 + np.sqrt(np.maximum(0.0, 1.0 - p1 * p1 - p2 * p2))[:, None] * s
    m = np.stack([alpha * nh[:, 0], alpha * nh[:, 1], np.maximum(0.0, nh[:, 2])], axis=-1)
    return m / np.linalg.norm(m, axis=-1, keepdims=True)


def weights(alpha, eta, cos_v, pick_first, rng, n):
    v = np.array([np.sqrt(1.0 - cos_v ** 2), 0.0, cos_v])
    u_side = rng.random(n)
    h = sample_visible(alpha, v, rng.random(n), rng.random(n))
    v_h = h @ v
    f, cos_t = fresnel(v_h, eta)
    if pick_first:
        p = float(np.clip(fresnel(np.array(cos_v), eta)[0], 0.05, 0.95))
        reflect = u_side < p
        scale = np.where(reflect, f / p, (1.0 - f) / (1.0 - p))
        possible = reflect | (f < 1.0)  # a transmission at a totally reflecting normal is lost
    else:
        reflect = u_side < f
        scale = np.ones(n)
        possible = np.ones(n, dtype=bool)
    l = np.where(reflect[:, None], 2.0 * v_h[:, None] * h - v, (v_h / eta - cos_t)[:, None] * h - v / eta)
    right_side = np.where(reflect, l[:, 2] > 0.0, l[:, 2] < 0.0) & possible
    radiance = np.where(reflect, 1.0, 1.0 / eta ** 2)
    return np.where(right_side, scale * smith_g1(alpha, l, h) * radiance, 0.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--alpha", type=float, default=0.2)
    parser.add_argument("--ior", type=float, default=1.5046)
    parser.add_argument("--samples", type=int, default=400000)
    args = parser.parse_args()
    rng = np.random.default_rng(1)
    print("| light arrives | v.z | mean, old / new | second moment, old / new | largest, old / new |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for side, eta in (("from outside", args.ior), ("from inside", 1.0 / args.ior)):
        for cos_v in (0.95, 0.8, 0.6, 0.4, 0.2):
            old = weights(args.alpha, eta, cos_v, True, rng, args.samples)
            new = weights(args.alpha, eta, cos_v, False, rng, args.samples)
            print(f"| {side} | {cos_v} | {old.mean():.3f} / {new.mean():.3f} | "
                  f"{np.mean(old ** 2):.2f} / {np.mean(new ** 2):.2f} | {old.max():.1f} / {new.max():.2f} |")


if __name__ == "__main__":
    main()
