# The demo job (assets/bunny.toml) done in Blender, for scripts/demo_bench.py to time beside
# `shatter run assets/bunny.toml`:
#
#   blender -b --factory-startup --python bench/blender_demo.py -- MESH OUT_DIR [FRAMES]
#
# The bunny (MESH, 0.1 m per unit as the shot scales it: 20 cm long) is cut by the Cell Fracture
# add-on (object_fracture_cell) into 10 pieces; the pieces become active rigid bodies joined by
# breakable fixed constraints, one per touching pair (Blender's Connect tool, pair by pair); the
# whole drops from 1.5 m onto a passive ground plane; the rigid body cache is baked for FRAMES
# frames (default 90; demo_bench.py passes the frames shatter's run made, so that both jobs draw
# as many) at 30 fps; and the frames are rendered at 1280x720 with the Workbench engine into
# OUT_DIR/frame_NNNN.png. It prints one line "blender_demo: import S, fracture S, constraints S,
# bake S, render S (N pieces, M constraints, F frames)" with the seconds of each phase.
import os
import sys
import time

import bpy
from mathutils import Vector
from mathutils.kdtree import KDTree

FRAMES = 90             # frames when none are given
FPS = 30
PIECES = 10
SCALE = 0.1             # m per unit of the OBJ (assets/bunny.toml [mesh] scale)
DROP = 1.5              # m: the bunny's origin above the ground ([object] position)
TOUCH = 0.0025          # m: pieces with vertices this close touch (Cell Fracture leaves a 1 mm margin on each)
BREAKING_THRESHOLD = 2.0  # impulse (N s) a fixed constraint takes before it breaks


def phase(times, name, start):
    times.append((name, time.time() - start))
    return time.time()


def import_bunny(path):
    bpy.ops.object.select_all(action="SELECT")
    bpy.ops.object.delete()
    if hasattr(bpy.ops.wm, "obj_import"):
        bpy.ops.wm.obj_import(filepath=path)  # Y up in the file, Z up in Blender
    else:
        bpy.ops.import_scene.obj(filepath=path)
    obj = bpy.context.selected_objects[0]
    obj.scale = (SCALE, SCALE, SCALE)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.transform_apply(location=False, rotation=True, scale=True)
    obj.location = (0.0, 0.0, DROP)
    return obj


def fracture(obj):
    bpy.ops.preferences.addon_enable(module="object_fracture_cell")
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.add_fracture_cell_objects(source={"VERT_OWN"}, source_limit=PIECES, source_noise=0.0,
                                             use_debug_redraw=False, use_remove_original=True, use_island_split=False)
    return list(bpy.context.selected_objects)  # the add-on leaves its pieces selected


def touching_pairs(pieces):
    points = []
    for o in pieces:
        m = o.matrix_world
        points.append([m @ v.co for v in o.data.vertices])
    trees = []
    for pts in points:
        tree = KDTree(len(pts))
        for i, p in enumerate(pts):
            tree.insert(p, i)
        tree.balance()
        trees.append(tree)
    pairs = []
    for a in range(len(pieces)):
        for b in range(a + 1, len(pieces)):
            if any(trees[a].find_range(p, TOUCH) for p in points[b]):
                pairs.append((a, b))
    return pairs


def rigid_bodies(pieces):
    bpy.ops.object.select_all(action="DESELECT")
    for o in pieces:
        o.select_set(True)
    bpy.context.view_layer.objects.active = pieces[0]
    bpy.ops.rigidbody.objects_add(type="ACTIVE")
    for o in pieces:
        o.rigid_body.collision_shape = "CONVEX_HULL"
        o.rigid_body.friction = 0.6
        o.rigid_body.restitution = 0.1
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, 0.0))
    ground = bpy.context.active_object
    bpy.ops.rigidbody.object_add(type="PASSIVE")
    ground.rigid_body.friction = 0.6
    constraints = 0
    for a, b in touching_pairs(pieces):
        bpy.ops.object.select_all(action="DESELECT")
        pieces[a].select_set(True)
        pieces[b].select_set(True)
        bpy.context.view_layer.objects.active = pieces[a]
        bpy.ops.rigidbody.connect(con_type="FIXED", pivot_type="CENTER", connection_pattern="SELECTED_TO_ACTIVE")
        constraints += 1
    for o in bpy.context.scene.objects:
        if o.rigid_body_constraint:
            o.rigid_body_constraint.use_breaking = True
            o.rigid_body_constraint.breaking_threshold = BREAKING_THRESHOLD
    return constraints


def bake(scene, frames):
    scene.render.fps = FPS
    scene.frame_start = 1
    scene.frame_end = frames
    world = scene.rigidbody_world
    world.point_cache.frame_start = 1
    world.point_cache.frame_end = frames
    bpy.ops.ptcache.bake_all(bake=True)


def render(scene, out_dir):
    bpy.ops.object.camera_add(location=(0.7, -1.0, 0.5))
    camera = bpy.context.active_object
    direction = Vector((0.0, 0.0, 0.1)) - camera.location
    camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    camera.data.angle = 0.698  # 40 degrees, the shot's fov
    scene.camera = camera
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x = 1280
    scene.render.resolution_y = 720
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = os.path.join(os.path.abspath(out_dir), "frame_")
    bpy.ops.render.render(animation=True)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) not in (2, 3) or (len(argv) == 3 and not (argv[2].isdigit() and int(argv[2]) > 0)):
        sys.exit("usage: blender -b --factory-startup --python bench/blender_demo.py -- MESH OUT_DIR [FRAMES, "
                 "a whole number above 0, default %d]" % FRAMES)
    mesh, out_dir = argv[:2]
    frames = int(argv[2]) if len(argv) == 3 else FRAMES
    os.makedirs(out_dir, exist_ok=True)
    scene = bpy.context.scene
    times = []
    start = time.time()
    obj = import_bunny(mesh)
    start = phase(times, "import", start)
    pieces = fracture(obj)
    start = phase(times, "fracture", start)
    constraints = rigid_bodies(pieces)
    start = phase(times, "constraints", start)
    bake(scene, frames)
    start = phase(times, "bake", start)
    render(scene, out_dir)
    phase(times, "render", start)
    frames = len([f for f in os.listdir(out_dir) if f.startswith("frame_") and f.endswith(".png")])
    print("blender_demo: %s (%d pieces, %d constraints, %d frames)"
          % (", ".join("%s %.2f" % t for t in times), len(pieces), constraints, frames), flush=True)


main()
