# What a plane cut's cracks measure: a mesh cut by Blender's Cell Fracture add-on
# (object_fracture_cell, Voronoi cells: every crack a plane) into PIECES pieces, exported as a
# .glb whose crack faces have their own material (named "..._fracture", as shatter's .glb names
# them), and measured by scripts/crack_creases.py, for docs/log.md beside shatter's figures:
#
#   blender -b --factory-startup --python bench/blender_cracks.py -- MESH OUT.glb [SEED] [surface|volume] [PIECES]
#
# MESH: an .obj (Blender's importer), or a .3ds (read here: Blender 3.4 ships no 3DS importer),
# its identical vertices joined as shatter joins them; or a shatter run's .glb, whose pieces'
# outer and cavity faces (every material but the fracture one) are the surface cut, welded: the
# demo's hollow bunny (`shatter run assets/bunny.toml -o out/demo`, then out/demo/bunny.glb) is
# cut as shatter cut it, the same outer surface and the same cavity; an open mesh (glmark2's cat)
# as the solid shatter made of it, from a run with `--set prescore.render_surface=false` (the
# pieces' tet surfaces, closed). The mesh is scaled to 10 units long before
# the cut (Cell Fracture merges points within 0.005 units; the density is a ratio times the
# diagonal, so the scale does not enter it). The mesh must be closed (a warning says when not). The cells' seeds: "surface" (the default) takes
# PIECES of the mesh's own vertices at random, as Cell Fracture does by default; "volume" takes
# PIECES points uniform in the mesh's volume (as shatter's `seeds = "uniform"`), given to the
# add-on as a child object's vertices. SEED (default 1) seeds Python's random, which the add-on
# draws from. Prints one line "blender_cracks: ..." with the density, the share of creased edges
# and the number of pieces.
import os
import random
import struct
import sys

import bmesh
import bpy
import numpy
from mathutils import Vector
from mathutils.bvhtree import BVHTree

if "bool" not in numpy.__dict__:  # (asking hasattr warns)
    numpy.bool = bool  # the glTF add-on of Blender 3.4 still names numpy.bool

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import crack_creases  # noqa: E402  (standard library only)

LENGTH = 10.0  # units: the mesh's longest side before the cut


def read_3ds(path):
    """Every trimesh of a 3DS file: (vertices, triangles), the objects' vertices in one list."""
    with open(path, "rb") as f:
        data = f.read()
    vertices, triangles = [], []

    def walk(start, end):
        at = start
        while at + 6 <= end:
            chunk, length = struct.unpack_from("<HI", data, at)
            body, stop = at + 6, min(at + length, end)
            if length < 6:
                break
            if chunk in (0x4D4D, 0x3D3D, 0x4100):
                walk(body, stop)
            elif chunk == 0x4000:  # an object: its name, then its chunks
                walk(data.index(b"\0", body) + 1, stop)
            elif chunk == 0x4110:
                walk.base = len(vertices)
                n = struct.unpack_from("<H", data, body)[0]
                vertices.extend(struct.unpack_from("<%df" % (3 * n), data, body + 2)[i:i + 3] for i in range(0, 3 * n, 3))
            elif chunk == 0x4120:
                n = struct.unpack_from("<H", data, body)[0]
                for i in range(n):
                    a, b, c, _ = struct.unpack_from("<4H", data, body + 2 + 8 * i)
                    triangles.append((walk.base + a, walk.base + b, walk.base + c))
            at += length

    walk.base = 0
    walk(0, len(data))
    return vertices, triangles


def read_glb_shell(path):
    """A shatter .glb's pieces, placed by their nodes, without their crack faces: (vertices,
    triangles), points within 1e-6 of the diagonal joined (each piece's own are its local ones
    plus its translation, rounded apart by a few ulps)."""
    doc, binary = crack_creases.read_glb(path)
    triangles_at = []
    for mesh_index, m in crack_creases.placed_meshes(doc):
        for prim in doc["meshes"][mesh_index]["primitives"]:
            name = doc["materials"][prim["material"]].get("name", "") if "material" in prim else ""
            if name.endswith("_fracture"):
                continue
            positions = crack_creases.accessor(doc, binary, prim["attributes"]["POSITION"])
            world = [tuple(sum(m[r][c] * p[c] for c in range(3)) + m[r][3] for r in range(3)) for p in positions]
            ids = crack_creases.accessor(doc, binary, prim["indices"])
            triangles_at.extend((world[ids[i]], world[ids[i + 1]], world[ids[i + 2]]) for i in range(0, len(ids) - 2, 3))
    lo = [min(p[i] for t in triangles_at for p in t) for i in range(3)]
    hi = [max(p[i] for t in triangles_at for p in t) for i in range(3)]
    grid = 1e-6 * sum((b - a) ** 2 for a, b in zip(lo, hi)) ** 0.5
    index, vertices, triangles = {}, [], []
    for t in triangles_at:
        tri = []
        for p in t:
            key = tuple(round(x / grid) for x in p)
            if key not in index:
                index[key] = len(vertices)
                vertices.append(p)
            tri.append(index[key])
        if len(set(tri)) == 3:
            triangles.append(tuple(tri))
    return vertices, triangles


def import_mesh(path):
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.object.delete()
    if path.lower().endswith((".3ds", ".glb")):
        vertices, triangles = read_3ds(path) if path.lower().endswith(".3ds") else read_glb_shell(path)
        mesh = bpy.data.meshes.new("object")
        mesh.from_pydata(vertices, [], triangles)
        mesh.update()
        obj = bpy.data.objects.new("object", mesh)
        bpy.context.collection.objects.link(obj)
    else:
        if hasattr(bpy.ops.wm, "obj_import"):
            bpy.ops.wm.obj_import(filepath=path)
        else:
            bpy.ops.import_scene.obj(filepath=path)
        obj = bpy.context.selected_objects[0]
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.mesh.remove_doubles(threshold=1e-7)  # identical vertices joined
    bpy.ops.object.mode_set(mode="OBJECT")
    longest = max(obj.dimensions)
    obj.scale = (LENGTH / longest,) * 3
    bpy.ops.object.transform_apply(location=True, rotation=True, scale=True)
    # The boolean that cuts each cell from the object needs it closed: around an open mesh it
    # keeps whole cells (glmark2's cat gave crack areas two to five times shatter's). Such a mesh
    # is better given as a shatter run's .glb with `--set prescore.render_surface=false` (its tet
    # surface: closed).
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    open_edges = sum(1 for e in bm.edges if len(e.link_faces) != 2)
    bm.free()
    if open_edges:
        print("blender_cracks: warning: %d open or non-manifold edges; the cut may keep whole cells" % open_edges,
              flush=True)
    obj.data.materials.clear()
    for p in obj.data.polygons:
        p.material_index = 0
    return obj


def volume_points(obj, count, rng):
    """count points uniform in obj's volume (inside: the nearest face's normal points away)."""
    tree = BVHTree.FromObject(obj, bpy.context.evaluated_depsgraph_get())
    lo = Vector([min(v.co[i] for v in obj.data.vertices) for i in range(3)])
    hi = Vector([max(v.co[i] for v in obj.data.vertices) for i in range(3)])
    points = []
    while len(points) < count:
        p = Vector([lo[i] + rng.random() * (hi[i] - lo[i]) for i in range(3)])
        hit, normal, _, _ = tree.find_nearest(p)
        if hit is not None and (p - hit).dot(normal) < 0:
            points.append(p)
    mesh = bpy.data.meshes.new("seeds")
    mesh.from_pydata([tuple(p) for p in points], [], [])
    seeds = bpy.data.objects.new("seeds", mesh)
    bpy.context.collection.objects.link(seeds)
    seeds.parent = obj
    return seeds


def fracture(obj, pieces, points):
    bpy.ops.preferences.addon_enable(module="object_fracture_cell")
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    # material_index 1: the cells' faces (the cracks) keep index 1 through the boolean, the
    # object's own faces index 0.
    bpy.ops.object.add_fracture_cell_objects(
        source={"VERT_OWN"} if points == "surface" else {"VERT_CHILD"}, source_limit=pieces if points == "surface" else 0,
        source_noise=0.0, use_debug_redraw=False, use_remove_original=True, use_island_split=False,
        material_index=1, use_sharp_edges=False, use_sharp_edges_apply=False, use_interior_vgroup=False)
    return [o for o in bpy.context.selected_objects if o.type == "MESH" and o.name != "seeds"]


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not 2 <= len(argv) <= 5 or (len(argv) > 3 and argv[3] not in ("surface", "volume")):
        sys.exit("usage: blender -b --factory-startup --python bench/blender_cracks.py -- MESH OUT.glb "
                 "[SEED] [surface|volume] [PIECES]")
    mesh, out = argv[:2]
    seed = int(argv[2]) if len(argv) > 2 else 1
    points = argv[3] if len(argv) > 3 else "surface"
    pieces = int(argv[4]) if len(argv) > 4 else 10
    random.seed(seed)  # the add-on's shuffle and its hull jitter draw from Python's random
    obj = import_mesh(mesh)
    if points == "volume":
        volume_points(obj, pieces, random.Random(seed))
    cells = fracture(obj, pieces, points)
    outer = bpy.data.materials.new("object")
    inner = bpy.data.materials.new("object_fracture")
    for o in cells:
        indices = [p.material_index for p in o.data.polygons]
        o.data.materials.clear()
        o.data.materials.append(outer)
        o.data.materials.append(inner)
        for p, i in zip(o.data.polygons, indices):
            p.material_index = 1 if i == 1 else 0
    bpy.ops.object.select_all(action="DESELECT")
    for o in cells:
        o.select_set(True)
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    bpy.ops.export_scene.gltf(filepath=out, export_format="GLB", use_selection=True, export_materials="EXPORT")
    r = crack_creases.measure(out)
    print("blender_cracks: %s seed %d %s: crease density %.2f, %.1f%% of %d inner crack edges creased, %d pieces "
          "(%d cut), crack area %.4g of the diagonal squared"
          % (os.path.basename(mesh), seed, points, r["density"], 100 * r["share"], r["inner_edges"], r["pieces"],
             len(cells), r["crack_area_m2"] / r["diagonal_m"] ** 2), flush=True)


main()
