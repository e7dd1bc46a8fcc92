#!/usr/bin/python3
"""Makes docs/images/blender-bunny.png: Blender's window after Object > Shatter, on a virtual display.

  scripts/blender_screenshot.py BUILD OUT.png      (`make blender-screenshot`)

Run by Python, it installs the add-on from BUILD/shatter_blender.zip into BUILD/blender-user
(never the user's own Blender folders), and starts Debian's Blender with a window on a virtual
X display (xvfb-run: `apt-get install xvfb`) running this file again. Inside Blender it builds
the scene (glmark2's bunny, 20 cm, 1 m above a floor slab), calls the operator as the menu does
(modal, with its progress in the status bar), waits for it, shows the frame 0.2 s after the
first break in the viewport, and saves the window, reduced to 256 colours to keep the PNG small.
"""

import os
import shutil
import subprocess
import sys

WIDTH, HEIGHT = 1280, 720

try:
    import bpy
except ImportError:
    bpy = None


def driver():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    build, out = (os.path.abspath(p) for p in sys.argv[1:])
    blender, xvfb = shutil.which("blender"), shutil.which("xvfb-run")
    if not blender or not xvfb:
        print("blender_screenshot: needs blender and xvfb-run (apt-get install blender xvfb)")
        return 1
    user = os.path.join(build, "blender-user", "screenshot")
    shutil.rmtree(user, ignore_errors=True)
    os.makedirs(os.path.join(user, "tmp"))
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(user, "scripts"),
               BLENDER_USER_CONFIG=os.path.join(user, "config"), TMPDIR=os.path.join(user, "tmp"))
    # Preferences without the first start's splash screen, saved where this Blender reads them.
    subprocess.run([blender, "-b", "--factory-startup", "--python-expr",
                    "import bpy; v = bpy.context.preferences.view; v.show_splash = False; v.show_tooltips = False; "
                    "bpy.ops.wm.save_userpref()"],
                   env=env, check=True, stdout=subprocess.DEVNULL)
    argv = [xvfb, "-a", "-s", f"-screen 0 {WIDTH}x{HEIGHT}x24", blender, "--window-geometry", "0", "0",
            str(WIDTH), str(HEIGHT), "--python", os.path.abspath(__file__), "--",
            os.path.join(build, "shatter_blender.zip"), os.path.join(build, "bin", "shatter"),
            os.path.join(user, "runs"), out]
    code = subprocess.run(argv, env=env, timeout=600).returncode
    if code == 0 and os.path.isfile(out):
        print(f"blender_screenshot: {out} ({os.path.getsize(out) // 1024} KB)")
    return code


def inside_blender():
    import time

    zip_path, shatter, runs, out = sys.argv[sys.argv.index("--") + 1:]
    state = {"phase": "setup"}

    def window_context():
        win = bpy.context.window_manager.windows[0]
        area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
        region = next(r for r in area.regions if r.type == "WINDOW")
        return win, area, region

    def setup():
        bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
        bpy.ops.preferences.addon_enable(module="shatter_blender")
        prefs = bpy.context.preferences.addons["shatter_blender"].preferences
        prefs.shatter_binary, prefs.output_folder = shatter, runs
        for o in list(bpy.data.objects):
            if o.type == "MESH":
                bpy.data.objects.remove(o)
        scene = bpy.context.scene
        scene.render.fps = 30
        win, area, region = window_context()
        with bpy.context.temp_override(window=win, area=area, region=region):
            bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, -0.05), scale=(3, 3, 0.1))
            floor = bpy.context.active_object
            floor.name = "Floor"
            bpy.ops.wm.obj_import(filepath="/usr/share/glmark2/models/bunny.obj")
            bunny = bpy.context.selected_objects[0]
            bunny.scale = (0.1, 0.1, 0.1)
            bunny.location = (0.0, 0.0, 1.0)
            bunny.rotation_euler[2] = 0.6
            material = bpy.data.materials.new("Terracotta")
            material.diffuse_color = (0.62, 0.25, 0.12, 1.0)
            material.use_nodes = True
            material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.62, 0.25, 0.12, 1.0)
            bunny.data.materials.append(material)
            bpy.context.view_layer.objects.active = bunny
            win.cursor_warp(330, 170)   # the result's popup opens at the pointer: over the floor, below the pieces
            result = bpy.ops.object.shatter("EXEC_DEFAULT", pieces=20, drop="SCENE")
        if result != {"RUNNING_MODAL"}:
            raise SystemExit(f"blender_screenshot: the operator returned {result}, not a modal run")
        state.update(phase="running", start=time.monotonic())

    def show(root):
        import json

        from mathutils import Euler, Vector
        scene = bpy.context.scene
        with open(os.path.join(root["shatter_folder"], "summary.json"), encoding="utf-8") as f:
            first_break = json.load(f)["simulation"]["first_break_s"]
        scene.frame_set(scene.frame_start + round((first_break + 0.3) * scene.render.fps))
        pieces = [o for o in root.children]
        centre = sum((o.matrix_world.translation for o in pieces), Vector()) / len(pieces)
        win, area, region = window_context()
        space = area.spaces.active
        space.shading.type = "SOLID"
        space.shading.color_type = "MATERIAL"
        space.shading.show_shadows = True
        space.shading.show_cavity = True
        space.overlay.show_relationship_lines = False
        space.show_region_toolbar = False
        r3d = space.region_3d
        r3d.view_perspective = "PERSP"
        r3d.view_rotation = Euler((1.1, 0.0, 0.75)).to_quaternion()
        r3d.view_location = centre + Vector((0.0, 0.0, 0.03))
        r3d.view_distance = 0.75
        for a in win.screen.areas:
            if a.type == "PROPERTIES":
                a.spaces.active.context = "OBJECT"
            if a.type == "OUTLINER":
                with bpy.context.temp_override(window=win, area=a, region=a.regions[-1]):
                    bpy.ops.outliner.show_one_level()
        for o in bpy.context.view_layer.objects:
            o.select_set(False)
        bpy.context.view_layer.objects.active = root

    def tick():
        phase = state["phase"]
        if phase == "setup":
            setup()
            return 0.5
        roots = [o for o in bpy.data.objects if "shatter_folder" in o]
        if phase == "running":
            if roots:
                show(roots[0])
                state.update(phase="shoot", at=time.monotonic())
            elif time.monotonic() - state["start"] > 300:
                print("blender_screenshot: no result after 300 s")
                bpy.ops.wm.quit_blender()
                return None
            return 0.5
        if time.monotonic() - state["at"] < 2.0:   # let the window redraw
            return 0.5
        win, area, region = window_context()
        raw = out + ".full.png"
        with bpy.context.temp_override(window=win, area=area, region=region):
            bpy.ops.screen.screenshot(filepath=raw)
        from PIL import Image
        Image.open(raw).convert("RGB").quantize(256, dither=Image.Dither.NONE).save(out, optimize=True)
        os.remove(raw)
        bpy.ops.wm.quit_blender()
        return None

    bpy.app.timers.register(tick, first_interval=1.0)


if __name__ == "__main__":
    if bpy is None:
        sys.exit(driver())
    inside_blender()
