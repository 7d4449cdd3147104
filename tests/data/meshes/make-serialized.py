#!/usr/bin/env python3
"""Writes two-meshes.serialized, the .serialized test file that Mitsuba 3.9.1
reads in tests/scene/test_mesh_serialized.cpp's reference values: version 4,
mesh 0 in single precision with vertex normals and texture coordinates,
mesh 1 in double precision with vertex colours and the face-normals flag.
Written from the format's description in Mitsuba's documentation (Mitsuba 3
reads .serialized but cannot write it):  python3 make-serialized.py"""
import os
import struct
import zlib


def mesh(name, pos, tris, normals=None, uvs=None, colors=None, double=False, face_normals=False):
    flags = ((1 if normals else 0) | (2 if uvs else 0) | (8 if colors else 0)
             | (0x10 if face_normals else 0) | (0x2000 if double else 0x1000))
    f = 'd' if double else 'f'
    body = struct.pack('<I', flags) + name.encode() + b'\0' + struct.pack('<QQ', len(pos), len(tris))
    for arr in (pos, normals, uvs, colors):
        for v in arr or []:
            body += struct.pack('<%d%s' % (len(v), f), *v)
    for t in tris:
        body += struct.pack('<3I', *t)
    return struct.pack('<HH', 0x041C, 4) + zlib.compress(body)


pos = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0.5)]
tris = [(0, 1, 2), (1, 3, 2)]
m0 = mesh('first', pos, tris, normals=[(0, 0, 1), (0, 0.6, 0.8), (0, 0, 1), (0.6, 0, 0.8)],
          uvs=[(0, 0), (1, 0), (0, 1), (1, 1)])
m1 = mesh('second', [(x + 2, y, z) for x, y, z in pos], tris,
          colors=[(1, 0, 0)] * 4, double=True, face_normals=True)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'two-meshes.serialized')
with open(out, 'wb') as f:
    f.write(m0 + m1 + struct.pack('<QQI', 0, len(m0), 2))
