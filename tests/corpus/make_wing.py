#!/usr/bin/python3
"""Writes wing.stl: a thin, large, self-intersecting wing like the one that once made prescore
run without end (177 x 55 x 3 units, 842 triangles). Two tapered, cambered slabs, the second
turned 4 degrees about the span and crossing the first, so that their skins cut through each
other along most of the span. Binary STL, no units. Run: python3 make_wing.py > wing.stl"""
import math
import struct
import sys


def slab(nx, nz, length, chord, thick, twist):
    """A closed, cambered slab: nx x nz quads on top and bottom, plus its rim."""
    top, bot = [], []
    for i in range(nx + 1):
        x = length * i / nx
        c = chord * (1 - 0.5 * i / nx)  # tapered
        row_t, row_b = [], []
        for k in range(nz + 1):
            u = k / nz
            z = c * (u - 0.5)
            camber = 2.0 * math.sin(math.pi * u)
            t = thick * 0.5 * math.sin(math.pi * u) ** 0.5 + 0.05
            y_t, y_b = camber + t, camber - t
            ca, sa = math.cos(twist), math.sin(twist)
            row_t.append((x, y_t * ca - z * sa, y_t * sa + z * ca))
            row_b.append((x, y_b * ca - z * sa, y_b * sa + z * ca))
        top.append(row_t)
        bot.append(row_b)
    tris = []
    for i in range(nx):
        for k in range(nz):
            a, b, c, d = top[i][k], top[i + 1][k], top[i + 1][k + 1], top[i][k + 1]
            tris += [(a, c, b), (a, d, c)]
            a, b, c, d = bot[i][k], bot[i + 1][k], bot[i + 1][k + 1], bot[i][k + 1]
            tris += [(a, b, c), (a, c, d)]
    for i in range(nx):  # leading and trailing rims
        for k in (0, nz):
            a, b, c, d = top[i][k], top[i + 1][k], bot[i + 1][k], bot[i][k]
            tris += [(a, b, c), (a, c, d)] if k == 0 else [(a, c, b), (a, d, c)]
    for i in (0, nx):  # root and tip
        for k in range(nz):
            a, b, c, d = top[i][k], top[i][k + 1], bot[i][k + 1], bot[i][k]
            tris += [(a, c, b), (a, d, c)] if i == 0 else [(a, b, c), (a, c, d)]
    return tris


tris = slab(20, 9, 177, 55, 1.5, 0.0) + slab(20, 9, 177, 50, 1.5, math.radians(4))
out = sys.stdout.buffer
out.write(b"wing: two crossing slabs".ljust(80, b" "))
out.write(struct.pack("<I", len(tris)))
for t in tris:
    out.write(struct.pack("<3f", 0, 0, 0))
    for p in t:
        out.write(struct.pack("<3f", *p))
    out.write(b"\0\0")
