"""The Blender add-on in a real Blender, headless; run by tests/blender/run_addon_test.py:

  blender -b --factory-startup --python-exit-code 1 --python addon_test.py -- \
      --case CASE --zip shatter_blender.zip --shatter SHATTER --work DIR

Every case installs and enables the add-on from the built .zip first (into the user scripts
folder the driver points BLENDER_USER_SCRIPTS at), then:

  fractures_in_place   glmark2's bunny (20 cm, moved and turned), Object > Shatter in 10 pieces:
                       10 animated pieces whose volume centroids at the last frame lie within
                       1 mm of the centres of mass shatter's trajectory gives
                       (`shatter info TRAJ --json`), keys on the scene's frames, the original
                       hidden and unchanged, the report page linked.
  units_and_frame_rate a scene in centimetres at 29.97 fps starting at frame 11, the bunny dropped
                       "as placed" onto a slab for 40 frames: the same checks, and the pieces
                       at rest on the slab.
  refused_mesh         a mesh shatter refuses (tests/bad_inputs/mesh-degenerate.obj: no area):
                       the operator fails with shatter's message and the scene is as it was.
  no_binary            the preferences name a binary that is not there: a clear error, the scene
                       as it was.

An assertion that fails raises, and Blender exits with 1.
"""

import argparse
import hashlib
import json
import math
import os
import subprocess
import sys
import time

import bpy

BUNNY = "/usr/share/glmark2/models/bunny.obj"
TOLERANCE_M = 1e-3
# A piece is drawn with its render surface (the input cut along its fracture faces), its mass is its
# tets': their volumes differ by a few percent (measured: up to 10%), pieces' by up to 8 times.
VOLUME_TOLERANCE = 0.2


def args():
    p = argparse.ArgumentParser()
    p.add_argument("--case", required=True, choices=["fractures_in_place", "units_and_frame_rate", "refused_mesh", "no_binary"])
    p.add_argument("--zip", required=True)
    p.add_argument("--shatter", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--source", required=True, help="the repository, for tests/bad_inputs/")
    return p.parse_args(sys.argv[sys.argv.index("--") + 1:])


def install_addon(zip_path, shatter, runs):
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    bpy.ops.preferences.addon_enable(module="shatter_blender")
    assert "shatter_blender" in bpy.context.preferences.addons, "the add-on did not enable"
    assert hasattr(bpy.ops.object, "shatter"), "bpy.ops.object.shatter is not registered"
    prefs = bpy.context.preferences.addons["shatter_blender"].preferences
    prefs.shatter_binary = shatter
    prefs.output_folder = runs


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)


def import_obj(path):
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path)
    (obj,) = set(bpy.data.objects) - before
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


def mesh_hash(mesh):
    h = hashlib.sha256()
    for v in mesh.vertices:
        h.update(repr(tuple(round(c, 9) for c in v.co)).encode())
    for p in mesh.polygons:
        h.update(repr(tuple(p.vertices)).encode())
    h.update(repr([m.name if m else None for m in mesh.materials]).encode())
    return h.hexdigest()


def scene_state():
    """Everything a failed run must leave as it was."""
    scene, layer = bpy.context.scene, bpy.context.view_layer
    objects = {o.name: (tuple(tuple(round(x, 9) for x in row) for row in o.matrix_world), o.hide_get(),
                        o.hide_render, o.select_get(), o.data.name if o.data else None,
                        tuple(c.name for c in o.users_collection)) for o in layer.objects}
    data = {kind: sorted(getattr(bpy.data, kind).keys())
            for kind in ("objects", "meshes", "materials", "images", "actions", "cameras", "collections")}
    meshes = {m.name: mesh_hash(m) for m in bpy.data.meshes}
    return {"objects": objects, "data": data, "meshes": meshes,
            "active": layer.objects.active.name if layer.objects.active else None,
            "frames": (scene.frame_start, scene.frame_end, scene.frame_current),
            "engine": scene.render.engine, "scene_keys": sorted(scene.keys())}


def volume_centroid(obj):
    """The centroid of the volume the object's closed mesh bounds, in world coordinates, and its
    volume: a sum of signed tetrahedra over its triangles, in the object's own frame and in double
    precision (mathutils is single precision: world coordinates metres away from the origin would
    cancel to millimetres), then placed by the object's world matrix."""
    mesh = obj.data
    mesh.calc_loop_triangles()
    co = [tuple(v.co) for v in mesh.vertices]
    volume, moment = 0.0, [0.0, 0.0, 0.0]
    for tri in mesh.loop_triangles:
        a, b, c = (co[i] for i in tri.vertices)
        v = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
             + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
        volume += v
        for k in range(3):
            moment[k] += v * (a[k] + b[k] + c[k]) / 4.0
    assert volume > 0, f"{obj.name}: its mesh bounds no volume ({volume})"
    local = [m / volume for m in moment]
    world = obj.matrix_world
    centroid = [sum(world[r][k] * local[k] for k in range(3)) + world[r][3] for r in range(3)]
    scale = abs(world.to_3x3().determinant())
    return centroid, volume * scale


def shatter_json(shatter, *argv):
    out = subprocess.run([shatter, *argv, "--json"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def shatter_bunny(scale, location, **options):
    """glmark2's bunny (2 units wide in its file) at `scale` and `location`, turned 30 degrees, run
    through the operator with `options`. Returns (bunny, its matrix and mesh hash before, the run's
    root, its pieces in shatter's order, the operator's seconds)."""
    bunny = import_obj(BUNNY)
    bunny.scale = (scale, scale, scale)
    bunny.location = location
    bunny.rotation_euler = (0.0, 0.0, math.radians(30))
    bpy.context.view_layer.update()
    before = set(bpy.data.objects)
    state = (bunny.matrix_world.copy(), mesh_hash(bunny.data))

    start = time.monotonic()
    result = bpy.ops.object.shatter(**options)
    seconds = time.monotonic() - start
    assert result == {"FINISHED"}, result

    made = set(bpy.data.objects) - before
    pieces = sorted((o for o in made if "shatter_piece" in o), key=lambda o: o["shatter_piece"])
    roots = [o for o in made if "shatter_folder" in o]
    assert len(roots) == 1 and len(made) == len(pieces) + 1, f"made {sorted(o.name for o in made)}"
    assert [o["shatter_piece"] for o in pieces] == list(range(len(pieces)))
    for o in pieces:
        assert o.type == "MESH" and o.animation_data and o.animation_data.action, f"{o.name} is not animated"
        paths = {fc.data_path for fc in o.animation_data.action.fcurves}
        assert {"location", "rotation_quaternion"} <= paths, f"{o.name}: {paths}"
    return bunny, state, roots[0], pieces, seconds


def placed(position, xyzw, point, centre):
    """Where `point` of a piece (model frame) is when its centre of mass `centre` is at `position`,
    turned by the unit quaternion `xyzw`: position + R (point - centre)."""
    x, y, z, w = xyzw
    v = [point[k] - centre[k] for k in range(3)]
    # R v = v + 2 w (q x v) + 2 q x (q x v), q = (x, y, z)
    c = (y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0])
    cc = (y * c[2] - z * c[1], z * c[0] - x * c[2], x * c[1] - y * c[0])
    return [position[k] + v[k] + 2 * w * c[k] + 2 * cc[k] for k in range(3)]


def check_pieces(a, root, pieces):
    """The pieces against shatter's own files: a key per recorded frame from the scene's start
    frame, and each piece's volume centroid within TOLERANCE_M of its drawn surface's (the model's
    render_center_m: its frame is the world's) at the first frame and at the last (placed by the
    trajectory's final pose). Returns (the trajectory's summary, the farthest distance at the
    first and at the last frame in m)."""
    scene = bpy.context.scene
    folder = root["shatter_folder"]
    report = root["shatter_report"]
    assert os.path.isfile(report) and os.path.dirname(report) == folder, report
    traj = shatter_json(a.shatter, "info", os.path.join(folder, "bunny.traj"))
    model = shatter_json(a.shatter, "info", os.path.join(folder, "bunny.model"))
    fps = scene.render.fps / scene.render.fps_base
    assert traj["pieces"] == len(pieces) and abs(traj["fps"] - fps) < 1e-9, (traj["pieces"], traj["fps"], fps)
    frames = traj["frames"]

    keys = [kp.co.x for kp in pieces[0].animation_data.action.fcurves[0].keyframe_points]
    assert len(keys) == frames and keys[0] == scene.frame_start and keys[-1] == scene.frame_start + frames - 1, \
        (len(keys), keys[:2], keys[-2:], frames)
    assert scene.frame_end >= keys[-1]

    # shatter's world: Y up, metres; Blender's: Z up, scene units. A piece is drawn with its render
    # surface, whose volume centroid (render_center_m) lies off its tets' centre of mass: at the
    # first frame where the model has it, at the last turned as the piece is (final_rotation_xyzw).
    unit = scene.unit_settings.scale_length
    drawn = [p.get("render_center_m") or p["center_m"] for p in model["per_piece"]]
    last = [placed(t["final_position_m"], t["final_rotation_xyzw"], d, p["center_m"])
            for t, d, p in zip(traj["per_piece"], drawn, model["per_piece"])]
    worst = []
    for when, frame, centres in (("first", keys[0], drawn), ("last", keys[-1], last)):
        scene.frame_set(int(frame))
        worst.append(0.0)
        for o, (x, y, z), piece in zip(pieces, centres, model["per_piece"]):
            centroid, volume = volume_centroid(o)
            d = math.dist(centroid, (x / unit, -z / unit, y / unit)) * unit
            ratio = volume * unit ** 3 / (piece.get("render_volume_m3") or piece["volume_m3"])
            print(f"addon_test: {when} frame {frame:g}: {o.name}: volume centroid {d * 1000:.3f} mm from the "
                  f"centre of mass; volume {ratio:.3f} x its tets'")
            worst[-1] = max(worst[-1], d)
            assert d <= TOLERANCE_M, (f"{o.name}: at the {when} frame its volume centroid is {d * 1000:.3f} mm from "
                                      f"the centre of mass shatter gives")
            assert abs(ratio - 1) < VOLUME_TOLERANCE, f"{o.name}: volume {ratio:.3f} x its tets' (another piece's mesh?)"
    return traj, worst[0], worst[1]


def check_original(bunny, state):
    matrix, mesh = state
    assert bunny.name in bpy.data.objects and bunny.hide_get() and bunny.hide_render, "the original is not hidden"
    assert mesh_hash(bunny.data) == mesh, "the original's mesh changed"
    assert all(abs(x - y) < 1e-9 for rx, ry in zip(bunny.matrix_world, matrix) for x, y in zip(rx, ry)), \
        "the original moved"


def case_fractures_in_place(a):
    """The issue's case: the bunny (20 cm, as the demo's), bpy.ops.object.shatter(pieces=10)."""
    clear_scene()
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = 24, 1.0
    bunny, state, root, pieces, seconds = shatter_bunny(0.1, (0.3, -0.2, 0.5), pieces=10)
    assert len(pieces) == 10, f"{len(pieces)} pieces, not 10"
    traj, first, last = check_pieces(a, root, pieces)
    check_original(bunny, state)
    print(f"addon_test: fractures_in_place: 10 pieces, {traj['frames']} frames; the farthest volume centroid from "
          f"its centre of mass {first * 1000:.3f} mm at the first frame, {last * 1000:.3f} mm at the last "
          f"(tolerance {TOLERANCE_M * 1000:g} mm); the operator took {seconds:.1f} s")


def case_units_and_frame_rate(a):
    """A scene in centimetres at 29.97 fps, the bunny 1 m above a floor slab, dropped "as placed"
    for 40 frames: the same centroids, 40 keys on whole frames, and the pieces on the slab's top."""
    clear_scene()
    scene = bpy.context.scene
    scene.unit_settings.system, scene.unit_settings.scale_length = "METRIC", 0.01
    scene.render.fps, scene.render.fps_base = 30, 1.001
    scene.frame_start = 11
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, -5.0), scale=(300.0, 300.0, 10.0))
    floor_top = 0.0                                     # cm: the slab spans z -10 to 0
    bunny, state, root, pieces, seconds = shatter_bunny(10.0, (20.0, 10.0, 112.0), pieces=6, frames=40,
                                                        drop="SCENE", movie=False)
    traj, first, last = check_pieces(a, root, pieces)
    assert traj["frames"] == 40, traj["frames"]
    check_original(bunny, state)
    lowest = min((o.matrix_world @ v.co).z for o in pieces for v in o.data.vertices)
    print(f"addon_test: units_and_frame_rate: the pieces' lowest point {lowest:.3f} cm, the slab's top "
          f"{floor_top:g} cm")
    assert abs(lowest - floor_top) < 1.0, f"the pieces rest at z = {lowest:.3f} cm, not on the slab (z = 0)"
    print(f"addon_test: units_and_frame_rate: {len(pieces)} pieces, 40 frames at {traj['fps']:.4f} fps; "
          f"the farthest volume centroid {first * 1000:.3f} mm / {last * 1000:.3f} mm from its centre of mass; "
          f"the operator took {seconds:.1f} s")


def refusal(case, call, what):
    """Runs the operator expecting it to refuse: its message, the scene left as it was."""
    state = scene_state()
    try:
        call()
    except RuntimeError as e:
        message = str(e)
    else:
        raise AssertionError(f"the operator ran {what}")
    print(f"addon_test: {case}: {message}")
    assert scene_state() == state, "the scene changed"
    return message


def case_refused_mesh(a):
    obj = import_obj(os.path.join(a.source, "tests", "bad_inputs", "mesh-degenerate.obj"))
    message = refusal("refused_mesh", lambda: bpy.ops.object.shatter(pieces=10), "on a mesh shatter refuses")
    assert "the mesh has no area" in message and "fix:" in message, message
    assert not obj.hide_get()


def case_no_binary(a):
    bpy.context.preferences.addons["shatter_blender"].preferences.shatter_binary = os.path.join(a.work, "no-such-shatter")
    message = refusal("no_binary", lambda: bpy.ops.object.shatter(), "without a shatter binary")
    assert "no-such-shatter" in message and "Preferences" in message, message


def main():
    a = args()
    install_addon(a.zip, a.shatter, os.path.join(a.work, "runs"))
    {"fractures_in_place": case_fractures_in_place, "units_and_frame_rate": case_units_and_frame_rate,
     "refused_mesh": case_refused_mesh, "no_binary": case_no_binary}[a.case](a)
    print(f"addon_test: {a.case}: passed")


main()
