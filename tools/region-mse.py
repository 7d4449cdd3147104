#!/usr/bin/env python3
"""MSE and relMSE of images against a reference, near the light and elsewhere.

"Near the light" is every pixel whose reference value (largest channel) exceeds
--threshold (the light seen directly or in a mirror: it reads about 100 where
the walls read about 1), dilated by --dilate pixels (a square), where a
pixel's samples read either the light or what lies beside it. The two parts'
MSE are given as shares of the whole image's MSE (they sum to it), as in
../shared/measurements/README.md. Images are PFM or float32 OpenEXR (uncompressed or ZIP).

  tools/region-mse.py REFERENCE.pfm IMAGE.pfm [IMAGE.pfm ...]
"""
import argparse
import struct
import sys
import zlib

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            sys.exit(f"{path}: not a colour PFM")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.fromfile(f, dtype="<f4" if scale < 0 else ">f4", count=width * height * 3)
    if data.size != width * height * 3:
        sys.exit(f"{path}: truncated")
    return data.reshape(height, width, 3)[::-1].astype(np.float64)  # PFM rows run bottom to top


def read_exr(path):
    """A float32 scanline OpenEXR, uncompressed or ZIP (as wavepath writes it)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x76\x2f\x31\x01":
        sys.exit(f"{path}: not an OpenEXR file")
    pos, channels, window, compression = 8, [], None, 0
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        end2 = data.index(b"\0", end + 1)
        size = struct.unpack_from("<i", data, end2 + 1)[0]
        value = data[end2 + 5:end2 + 5 + size]
        if name == "channels":
            q = 0
            while value[q] != 0:
                e = value.index(b"\0", q)
                channels.append((value[q:e].decode(), struct.unpack_from("<i", value, e + 1)[0]))
                q = e + 1 + 16
        elif name == "dataWindow":
            window = struct.unpack("<4i", value)
        elif name == "compression":
            compression = value[0]
        pos = end2 + 5 + size
    pos += 1
    if compression not in (0, 3) or any(t != 2 for _, t in channels):
        sys.exit(f"{path}: only float32, uncompressed or ZIP, is read here")
    x0, y0, x1, y1 = window
    width, height = x1 - x0 + 1, y1 - y0 + 1
    lines = 16 if compression == 3 else 1
    chunks = (height + lines - 1) // lines
    offsets = struct.unpack_from(f"<{chunks}Q", data, pos)
    names = sorted(c for c, _ in channels)
    image = np.zeros((height, width, 3))
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        block = data[offset + 8:offset + 8 + size]
        n = min(lines, y1 + 1 - y)
        raw_size = n * width * 4 * len(names)
        if size < raw_size:
            raw = np.frombuffer(zlib.decompress(block), dtype=np.uint8).astype(np.int64)
            # Undo the predictor: each byte was stored as its difference to the last + 128.
            t = (raw[0] + np.concatenate(([0], np.cumsum(raw[1:] - 128)))) & 0xFF
            half = (len(t) + 1) // 2
            out = np.empty(len(t), dtype=np.uint8)
            out[0::2] = t[:half]
            out[1::2] = t[half:]
            block = out.tobytes()
        values = np.frombuffer(block, dtype="<f4").reshape(n, len(names), width)
        for c, name in enumerate(names):
            if name in "RGB":
                image[y - y0:y - y0 + n, :, "RGB".index(name)] = values[:, c, :]
    return image


def read_image(path):
    return read_exr(path) if path.lower().endswith(".exr") else read_pfm(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("reference")
    parser.add_argument("images", nargs="+")
    parser.add_argument("--threshold", type=float, default=10.0)
    parser.add_argument("--dilate", type=int, default=2)
    args = parser.parse_args()
    ref = read_image(args.reference)
    seen = ref.max(axis=2) > args.threshold
    near = seen.copy()
    h, w = seen.shape
    for dy in range(-args.dilate, args.dilate + 1):
        for dx in range(-args.dilate, args.dilate + 1):
            shifted = np.zeros_like(seen)
            shifted[max(0, dy):h + min(0, dy), max(0, dx):w + min(0, dx)] = \
                seen[max(0, -dy):h + min(0, -dy), max(0, -dx):w + min(0, -dx)]
            near |= shifted
    print(f"near the light: {near.mean() * 100:.2f} % of pixels (reference > {args.threshold}, "
          f"dilated {args.dilate} px)")
    print("image MSE relMSE MSE_near_share MSE_elsewhere_share relMSE_near_share relMSE_elsewhere_share")
    for path in args.images:
        img = read_image(path)
        if img.shape != ref.shape:
            sys.exit(f"{path}: {img.shape[1]}x{img.shape[0]}, reference {w}x{h}")
        se = ((img - ref) ** 2).mean(axis=2)
        rse = ((img - ref) ** 2 / (ref ** 2 + 0.01)).mean(axis=2)
        n = se.size
        print(f"{path} {se.mean():.5g} {rse.mean():.5g} {se[near].sum() / n:.5g} "
              f"{se[~near].sum() / n:.5g} {rse[near].sum() / n:.5g} {rse[~near].sum() / n:.5g}")


if __name__ == "__main__":
    main()
