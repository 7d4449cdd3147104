#!/usr/bin/env python3
"""Writes a SIDE x SIDE 8-bit RGB PNG of 512-texel squares, with the standard
library only (zlib), for the stress case of the largest texture wavepath takes
(docs/stability.md, "Textures at their extremes"):

    python3 tools/big-texture-png.py 16384 /tmp/big.png
"""
import struct
import sys
import zlib

side = int(sys.argv[1])
out = sys.argv[2]


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


rows = []
for phase in (0, 1):
    row = bytearray(b"\0")  # filter type: none
    for x in range(side):
        v = 220 if (x // 512 + phase) % 2 else 20
        row += bytes((v, v, v))
    rows.append(bytes(row))
compressor = zlib.compressobj(1)
data = [compressor.compress(rows[(y // 512) % 2]) for y in range(side)]
data.append(compressor.flush())
with open(out, "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n")
    f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 2, 0, 0, 0)))
    f.write(chunk(b"IDAT", b"".join(data)))
    f.write(chunk(b"IEND", b""))
