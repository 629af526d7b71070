#!/usr/bin/env python3
"""Writes a closed triangle mesh of a capsule (binary STL) for mcws's mesh collision models.

The capsule runs along z from 0 to LENGTH with RADIUS; SEGMENTS around, RINGS per hemisphere
and BODY rings along the cylinder. Vertices lie on the true surface, so the mesh is inscribed
in the capsule primitive of the same size.

Usage: make_capsule_mesh.py RADIUS LENGTH SEGMENTS RINGS BODY OUT.stl
"""
import math
import struct
import sys


def capsule(radius, length, segments, rings, body):
    # Latitude rows from the bottom pole to the top pole.
    rows = []  # (z, r) per row
    for k in range(rings + 1):  # bottom hemisphere, pole to equator
        a = -math.pi / 2 + (math.pi / 2) * k / rings
        rows.append((radius * math.sin(a), radius * math.cos(a)))
    for k in range(1, body + 1):  # cylinder
        rows.append((length * k / body, radius))
    for k in range(1, rings + 1):  # top hemisphere, equator to pole
        a = (math.pi / 2) * k / rings
        rows.append((length + radius * math.sin(a), radius * math.cos(a)))
    ring = lambda z, r: [(r * math.cos(2 * math.pi * j / segments),
                          r * math.sin(2 * math.pi * j / segments), z) for j in range(segments)]
    triangles = []
    for (z0, r0), (z1, r1) in zip(rows, rows[1:]):
        lo, hi = ring(z0, r0), ring(z1, r1)
        for j in range(segments):
            n = (j + 1) % segments
            if r0 > 1e-12:
                triangles.append((lo[j], lo[n], hi[n] if r1 > 1e-12 else hi[0]))
            if r1 > 1e-12:
                triangles.append((lo[j] if r0 > 1e-12 else lo[0], hi[n], hi[j]))
    return triangles


def main():
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    radius, length = float(sys.argv[1]), float(sys.argv[2])
    segments, rings, body = int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
    triangles = capsule(radius, length, segments, rings, body)
    with open(sys.argv[6], "wb") as out:
        out.write(b"mcws capsule mesh".ljust(80, b" "))
        out.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            out.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for v in t:
                out.write(struct.pack("<3f", *v))
            out.write(struct.pack("<H", 0))
    print(f"{sys.argv[6]}: {len(triangles)} triangles", file=sys.stderr)


if __name__ == "__main__":
    main()
