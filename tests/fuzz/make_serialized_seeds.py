#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_serialized (tests/fuzz/corpus/fuzz_serialized/): small Mitsuba
serialized files (the layout of core/serialized_mesh.h) made here, valid ones of versions 3, 4 and
5 and a few broken ones. Run from anywhere; it overwrites the seeds."""
import os
import struct
import zlib

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "fuzz_serialized")


def mesh(version, positions, indices, normals=(), uvs=(), colors=(), double=False, name=b"m", counts=None):
    flags = (1 if normals else 0) | (2 if uvs else 0) | (8 if colors else 0) | (0x2000 if double else 0x1000)
    body = struct.pack("<I", flags)
    if version == 4:
        body += name + b"\0"
    vertices, faces = counts or (len(positions) // 3, len(indices) // 3)
    body += struct.pack("<QQ", vertices, faces)
    scalar = "d" if double else "f"
    for array in (positions, normals, uvs, colors):
        body += struct.pack("<%d%s" % (len(array), scalar), *array)
    body += struct.pack("<%dI" % len(indices), *indices)
    return body


def mesh_v5(positions, indices, normals=(), uvs=(), maps=False, attributes=False, flags=None):
    n = len(positions) // 3
    f = len(indices) // 3
    if flags is None:
        flags = 0x1000 | (1 if normals else 0) | (4 if uvs else 0)
    body = struct.pack("<II", flags, 1) + b"m" + struct.pack("<QQQQ", n, f, n if maps else 0, n if maps else 0)
    for v in range(n):
        record = list(positions[3 * v:3 * v + 3]) + (list(normals[3 * v:3 * v + 3]) or [0, 0, 0]) + \
            (list(uvs[2 * v:2 * v + 2]) or [0, 0])
        body += struct.pack("<8f", *record)
    for t in range(f):
        body += struct.pack("<4I", *indices[3 * t:3 * t + 3], 0)
    if maps:
        body += struct.pack("<%dI" % (2 * n), *(list(range(n)) * 2))
    body += struct.pack("<I", 2 if attributes else 0)
    if attributes:
        body += struct.pack("<I", 12) + b"vertex_color" + struct.pack("<BI", 0, 3) + struct.pack("<%df" % (3 * n), *([0.5] * 3 * n))
        body += struct.pack("<I", 7) + b"face_id" + struct.pack("<BI", 0, 1) + struct.pack("<%df" % f, *([1.0] * f))
    return body


def serialized(version, contents):
    out, offsets = b"", []
    for c in contents:
        offsets.append(len(out))
        out += struct.pack("<HH", 0x041C, version) + zlib.compress(c, 9)
    out += struct.pack("<%d%s" % (len(offsets), "I" if version == 3 else "Q"), *offsets)
    return out + struct.pack("<I", len(offsets))


TRIANGLE = ([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 2])
QUAD = dict(positions=[0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], indices=[0, 1, 2, 0, 2, 3],
            normals=[0, 0, 1] * 4, uvs=[0, 0, 1, 0, 1, 1, 0, 1])

SEEDS = {
    "v3_triangle.serialized": serialized(3, [mesh(3, *TRIANGLE)]),
    "v4_two_meshes_normals_uvs.serialized": serialized(4, [mesh(4, *TRIANGLE), mesh(4, **QUAD)]),
    "v3_double_colors.serialized": serialized(3, [mesh(3, *TRIANGLE, colors=[1, 0, 0] * 3, double=True),
                                                  mesh(3, **QUAD, double=True)]),
    "v4_index_out_of_range.serialized": serialized(4, [mesh(4, TRIANGLE[0], [0, 1, 3])]),
    "v4_huge_counts.serialized": serialized(4, [mesh(4, *TRIANGLE, counts=(1 << 31, 1 << 30))]),
    "v4_more_data_than_counts.serialized": serialized(4, [mesh(4, **QUAD, counts=(4, 1))]),
    "v3_truncated.serialized": serialized(3, [mesh(3, **QUAD)])[:40],
    "v5_two_meshes_maps_attributes.serialized": serialized(5, [mesh_v5(*TRIANGLE),
                                                               mesh_v5(**QUAD, maps=True, attributes=True)]),
    "v5_frames.serialized": serialized(5, [mesh_v5(TRIANGLE[0], TRIANGLE[1], normals=[0, 0, 0, 0.15, 0, 0, 0, 0.1, 0.2],
                                                   flags=0x1013)]),
}

if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for name, data in SEEDS.items():
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(data)
        print(name, len(data), "bytes")
