#!/usr/bin/env python3
"""How creased a run's crack faces are, measured from its .glb (docs/render.md, "Faired cracks").

    scripts/crack_creases.py RUN.glb [--json] [--degrees 30]

Per piece (one glTF mesh per node), the triangles of its "fracture" materials (names ending in
"_fracture") are welded by position (equal float coordinates: one vertex). An edge with exactly
two such triangles is an inner edge of the crack; it is a crease when their normals differ by more
than --degrees. Printed:

  density  the crease length per unit of crack area, times the object's diagonal (the bounding box
           of every piece placed by its node's transform): about 4 / (tet size) x diagonal when
           every edge of equilateral facets is a crease, 0 for planes;
  share    the fraction of inner edges that are creases.

Degenerate triangles (area below 1e-12 of the diagonal squared) have no normal: their edges are
left out of both counts. Python's standard library only (struct and json).
"""
import argparse
import json
import math
import struct
import sys

COMPONENT = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2:
        raise SystemExit(f"{path}: not a binary glTF 2 file")
    doc, binary, at = None, b"", 12
    while at < length:
        size, kind = struct.unpack_from("<I4s", data, at)
        chunk = data[at + 8:at + 8 + size]
        if kind == b"JSON":
            doc = json.loads(chunk)
        elif kind == b"BIN\0":
            binary = chunk
        at += 8 + size
    return doc, binary


def accessor(doc, binary, index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    code, width = COMPONENT[a["componentType"]], WIDTH[a["type"]]
    item = struct.calcsize("<" + code)
    stride = view.get("byteStride", item * width)
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    out = []
    for i in range(a["count"]):
        values = struct.unpack_from("<" + code * width, binary, start + i * stride)
        out.append(values if width > 1 else values[0])
    return out


def node_matrix(node):
    """The node's local transform as a row-major 4x4 (glTF: a column-major matrix, or T R S)."""
    if "matrix" in node:
        m = node["matrix"]
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    s = node.get("scale", [1, 1, 1])
    t = node.get("translation", [0, 0, 0])
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[i][j] * s[j] for j in range(3)] + [t[i]] for i in range(3)] + [[0, 0, 0, 1]]


def multiply(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def placed_meshes(doc):
    """(mesh index, world matrix) of every node with a mesh."""
    out = []
    identity = [[float(i == j) for j in range(4)] for i in range(4)]

    def walk(index, parent):
        node = doc["nodes"][index]
        m = multiply(parent, node_matrix(node))
        if "mesh" in node:
            out.append((node["mesh"], m))
        for child in node.get("children", []):
            walk(child, m)

    scene = doc["scenes"][doc.get("scene", 0)]
    for root in scene["nodes"]:
        walk(root, identity)
    return out


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def crack_triangles(doc, binary, mesh):
    """The welded fracture triangles of one glTF mesh: (points, triangles)."""
    index, points, triangles = {}, [], []
    for prim in mesh["primitives"]:
        material = doc["materials"][prim["material"]].get("name", "") if "material" in prim else ""
        if not material.endswith("_fracture") or prim.get("mode", 4) != 4:
            continue
        positions = accessor(doc, binary, prim["attributes"]["POSITION"])
        ids = accessor(doc, binary, prim["indices"]) if "indices" in prim else list(range(len(positions)))
        for i in range(0, len(ids) - 2, 3):
            tri = []
            for k in range(3):
                p = tuple(positions[ids[i + k]])
                if p not in index:
                    index[p] = len(points)
                    points.append(p)
                tri.append(index[p])
            triangles.append(tri)
    return points, triangles


def measure(path, degrees=30.0):
    doc, binary = read_glb(path)
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for mesh_index, m in placed_meshes(doc):
        for prim in doc["meshes"][mesh_index]["primitives"]:
            for p in accessor(doc, binary, prim["attributes"]["POSITION"]):
                w = [sum(m[r][c] * p[c] for c in range(3)) + m[r][3] for r in range(3)]
                lo = [min(a, b) for a, b in zip(lo, w)]
                hi = [max(a, b) for a, b in zip(hi, w)]
    diagonal = norm(sub(hi, lo))
    cos_limit = math.cos(math.radians(degrees))
    area = crease_length = 0.0
    inner = creases = pieces = 0
    for mesh_index in sorted({i for i, _ in placed_meshes(doc)}):
        points, triangles = crack_triangles(doc, binary, doc["meshes"][mesh_index])
        if not triangles:
            continue
        pieces += 1
        normals, edges = [], {}
        for t, (a, b, c) in enumerate(triangles):
            n = cross(sub(points[b], points[a]), sub(points[c], points[a]))
            double_area = norm(n)
            area += double_area / 2
            normals.append(tuple(x / double_area for x in n) if double_area > 2e-12 * diagonal * diagonal else None)
            for u, v in ((a, b), (b, c), (c, a)):
                edges.setdefault((min(u, v), max(u, v)), []).append(t)
        for (u, v), around in edges.items():
            if len(around) != 2 or normals[around[0]] is None or normals[around[1]] is None:
                continue
            inner += 1
            n, m = normals[around[0]], normals[around[1]]
            if n[0] * m[0] + n[1] * m[1] + n[2] * m[2] < cos_limit:
                creases += 1
                crease_length += norm(sub(points[u], points[v]))
    return {
        "glb": path,
        "pieces": pieces,
        "diagonal_m": diagonal,
        "crack_area_m2": area,
        "inner_edges": inner,
        "creases": creases,
        "density": crease_length / area * diagonal if area > 0 else 0.0,
        "share": creases / inner if inner else 0.0,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("glb", nargs="+")
    parser.add_argument("--degrees", type=float, default=30.0, help="a crease is sharper than this (default 30)")
    parser.add_argument("--json", action="store_true", help="one JSON object per file")
    args = parser.parse_args()
    for path in args.glb:
        r = measure(path, args.degrees)
        if args.json:
            print(json.dumps(r))
        else:
            print(f"{path}: crease density {r['density']:.2f}, {100 * r['share']:.1f}% of {r['inner_edges']} inner "
                  f"crack edges sharper than {args.degrees:g} degrees ({r['pieces']} pieces, diagonal "
                  f"{r['diagonal_m']:.4g} m)")


if __name__ == "__main__":
    sys.exit(main())
