"""Object > Shatter: bpy.ops.object.shatter(), the active mesh object fractured by `shatter run`.

  start    the options checked, the object written to a temporary .glb (export_object), and
           `shatter run` started on it into the run's folder (shatter_process.py);
  wait     with a window: a modal operator whose timer polls the child and shows its stage in
           the status bar, Esc cancelling it; in background mode (blender -b), or called where
           there is no window: the child awaited in place;
  finish   the .glb shatter wrote imported into a new collection beside the object's, its keys
           put on the scene's frames from the start frame (shatter ran at the scene's frame
           rate), the object hidden (kept as it was).

The scene is touched only in finish, and a failure there removes whatever the import made: a run
that fails, is refused or is cancelled leaves the scene as it was. shatter's message reaches the
user as the operator's error report (a RuntimeError for a script calling it).
"""

import json
import math
import os
import re
import shutil
import tempfile

import bpy

from . import gltf_exchange, pieces, preferences, results, scene_measure, shatter_process, shot_settings

DEFAULT_DROP_M = 1.5          # m: the default shot's drop (docs/shot.md)
POLL_SECONDS = 0.25
EXIT_OK = 0
EXIT_UNSTABLE = 5             # the simulation stopped early: the valid frames are kept (docs/pipeline.md)
EXIT_TOOL = 6                 # ffmpeg missing or failing: the rest is there


# The run folders of the runs going on in this Blender: a run's folder is its own (a second run
# of an object while its first goes on takes the next name).
RUNNING = set()


class RunFailed(Exception):
    pass


class Job:
    """One run, from its start to its end."""

    def __init__(self, src_name, base, name, tmpdir, out_dir, drop_text):
        self.src_name = src_name
        self.base = base         # the run's name in the scene: NAME_shatter, NAME_piece_I
        self.name = name         # shatter's file names: NAME.glb, NAME.traj, ...
        self.tmpdir = tmpdir
        self.out_dir = out_dir
        self.drop_text = drop_text
        self.mesh_path = os.path.join(tmpdir, name + ".glb")
        self.process = None

    def message(self, code):
        """shatter's error, the object named where shatter names the temporary file."""
        return self.process.error_message(code).replace(self.mesh_path, f"'{self.src_name}'")

    @property
    def glb(self):
        return os.path.join(self.out_dir, self.name + ".glb")

    @property
    def report_page(self):
        return os.path.join(self.out_dir, "report.html")

    def summary(self):
        """The run's summary.json (docs/pipeline.md), {} when it cannot be read."""
        try:
            with open(os.path.join(self.out_dir, "summary.json"), encoding="utf-8") as f:
                return json.load(f)
        except (OSError, ValueError):
            return {}

    def frames(self):
        """The frames the run recorded (frame 0 at t = 0)."""
        frames = self.summary().get("simulation", {}).get("frames")
        if not isinstance(frames, int) or frames < 1:
            raise RunFailed(f"{os.path.join(self.out_dir, 'summary.json')} does not say how many frames the run has")
        return frames

    def clean(self):
        RUNNING.discard(self.out_dir)
        shutil.rmtree(self.tmpdir, ignore_errors=True)


def file_name(object_name):
    """The object's name as a file name: shatter names the run's files after it."""
    name = re.sub(r"[^A-Za-z0-9_.-]+", "_", object_name).strip("._")
    return name or "object"


def summary_line(summary):
    """A line about the run from its summary.json: joints broken, fragments, frames."""
    model, sim = summary.get("model", {}), summary.get("simulation", {})
    parts = []
    if "breaks" in sim and "constraints" in model:
        parts.append(f"{sim['breaks']} of {model['constraints']} joints broke")
    if "fragments" in sim:
        parts.append(f"{sim['fragments']} fragments")
    if "frames" in sim and "fps" in sim:
        parts.append(f"{sim['frames']} frames at {sim['fps']:g} fps")
    return ", ".join(parts)


class OBJECT_OT_shatter(bpy.types.Operator):
    """Fracture the active mesh object with shatter: it falls, breaks into animated pieces in its
    place (the object is hidden, not deleted)"""
    bl_idname = "object.shatter"
    bl_label = "Shatter"
    # UNDO: Ctrl+Z takes the pieces away and shows the object again. Not REGISTER: its redo panel
    # would run shatter again in place of the modal run after every change of an option.
    bl_options = {"UNDO"}

    pieces: bpy.props.IntProperty(
        name="Pieces", description="How many pieces the object is split into (prescore.pieces)",
        default=10, min=1, max=1000000, soft_max=1000)
    material: bpy.props.EnumProperty(
        name="Material",
        description="The material's published numbers (material.preset, docs/shot.md); Default: the default "
                    "shot's weak cast, which a drop shatters",
        items=[("DEFAULT", "Default (weak cast)", "The default shot's material: strength 20 kPa")]
        + [(p, p.replace("_", " ").capitalize(), f"material.preset = {p}") for p in shot_settings.PRESETS],
        default="DEFAULT")
    alpha: bpy.props.FloatProperty(
        name="Alpha", description="Share of a broken joint's stored energy given back as motion "
                                  "(material.alpha; 0: plain breaking, above 1 for effect)",
        default=1.0, min=0.0, max=100.0, soft_max=4.0)
    seed: bpy.props.IntProperty(
        name="Seed", description="Seed of where the pieces are cut and of the kicks' directions "
                                 "(prescore.seed, simulate.seed)",
        default=1, min=0)
    drop: bpy.props.EnumProperty(
        name="Drop",
        items=[("HEIGHT", "Drop height", "The ground is Drop Height below the object's lowest point"),
               ("SCENE", "As placed", "The ground is the scene's lowest surface below the object "
                                      "(the lowest top of the other visible meshes, else z = 0)")],
        default="HEIGHT")
    drop_height: bpy.props.FloatProperty(
        name="Drop Height", description="How far the object falls before it hits the ground (default 1.5 m)",
        default=DEFAULT_DROP_M, min=0.0, soft_max=100.0, subtype="DISTANCE", unit="LENGTH")
    frames: bpy.props.IntProperty(
        name="Frames", description="Frames of animation from the start frame; 0: auto, until the pieces rest "
                                   "(plus 0.5 s, at most 10 s)",
        default=0, min=0, soft_max=1000)
    movie: bpy.props.BoolProperty(
        name="Movie", description="Also draw shatter's movie and contact sheet for the report page "
                                  "(off: faster; the report has everything else)",
        default=True)

    _job = None
    _timer = None

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return context.mode == "OBJECT" and obj is not None and obj.type == "MESH"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        for name in ("pieces", "material", "alpha", "seed", "drop"):
            layout.prop(self, name)
        row = layout.row()
        row.enabled = self.drop == "HEIGHT"
        row.prop(self, "drop_height")
        layout.prop(self, "frames")
        layout.prop(self, "movie")

    def _default_drop(self, context):
        # 1.5 m whatever the scene's units (the property holds Blender units).
        if not self.properties.is_property_set("drop_height"):
            self.drop_height = DEFAULT_DROP_M / scene_measure.metres_per_unit(context.scene)

    def invoke(self, context, event):
        self._default_drop(context)
        return context.window_manager.invoke_props_dialog(self, width=340)

    def execute(self, context):
        self._default_drop(context)
        try:
            self._job = self._start(context)
        except (shot_settings.BadOption, shatter_process.ShatterNotFound, RunFailed) as e:
            self.report({"ERROR"}, f"Shatter: {e}")
            return {"CANCELLED"}
        if bpy.app.background or context.window is None:
            return self._finish(context, self._job.process.wait())
        wm = context.window_manager
        self._timer = wm.event_timer_add(POLL_SECONDS, window=context.window)
        wm.modal_handler_add(self)
        context.workspace.status_text_set(self._job.process.status() + "  (Esc: cancel)")
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC" and event.value == "PRESS":
            self._job.process.cancel()
            self._end_ui(context)
            self._job.clean()
            self._job = None
            self.report({"WARNING"}, "Shatter: cancelled; the scene is as it was")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        code = self._job.process.poll()
        if code is None:
            context.workspace.status_text_set(self._job.process.status() + "  (Esc: cancel)")
            return {"PASS_THROUGH"}
        self._end_ui(context)
        return self._finish(context, code)

    def cancel(self, context):
        # Blender ends the modal operator (a file loaded, Blender quit): stop the run too.
        if self._job is not None:
            self._job.process.cancel()
            self._job.clean()
            self._job = None
        self._end_ui(context)

    def _end_ui(self, context):
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        if context.workspace is not None:
            context.workspace.status_text_set(None)

    def _start(self, context):
        obj = context.active_object
        if obj is None or obj.type != "MESH":
            raise RunFailed("select a mesh object (the active object is what shatter fractures)")
        if not obj.hide_get() and not obj.visible_get():
            raise RunFailed(f"'{obj.name}' is not in the view layer: its collection is excluded or it is disabled "
                            "in viewports (fix: enable it in the outliner)")
        scene = context.scene
        unit = scene_measure.metres_per_unit(scene)
        fps = scene_measure.frame_rate(scene)
        bottom = scene_measure.lowest_point(obj, context.evaluated_depsgraph_get())
        if bottom is None:
            raise RunFailed(f"'{obj.name}' has no vertices")
        if self.drop == "HEIGHT":
            ground = bottom - self.drop_height
            drop_text = f"dropped {self.drop_height * unit:.3g} m"
        else:
            ground, what = scene_measure.scene_floor(context, obj, bottom)
            drop_text = f"dropped {(bottom - ground) * unit:.3g} m onto {what}"
        settings = shot_settings.shot_overrides(
            pieces=self.pieces, preset=self.material, alpha=self.alpha, seed=self.seed, ground_height_m=ground * unit,
            fps=fps, frames=self.frames, metres_per_unit=unit)
        binary = shatter_process.find_binary(preferences.preferences(context).shatter_binary)
        # One folder per result in the scene (an earlier result's report stays its own), the
        # stages that cost most shared between them by shatter's cache.
        runs = preferences.runs_folder(context)
        base = pieces.run_name(obj.name, lambda b: os.path.join(runs, file_name(b)) in RUNNING)
        out_dir = os.path.join(runs, file_name(base))
        tmpdir = tempfile.mkdtemp(prefix="shatter-blender-")
        job = Job(obj.name, base, file_name(obj.name), tmpdir, out_dir, drop_text)
        RUNNING.add(out_dir)
        try:
            os.makedirs(out_dir, exist_ok=True)
            gltf_exchange.export_object(context, obj, job.mesh_path)
            stages = None if self.movie else shot_settings.STAGES_WITHOUT_MOVIE
            job.process = shatter_process.ShatterProcess(shatter_process.run_command(
                binary, job.mesh_path, out_dir, settings, stages, cache=os.path.join(runs, ".cache")))
        except OSError as e:
            job.clean()
            raise RunFailed(f"could not start shatter: {e}") from e
        except Exception:
            job.clean()
            raise
        return job

    def _finish(self, context, code):
        job, self._job = self._job, None
        try:
            if code not in (EXIT_OK, EXIT_UNSTABLE, EXIT_TOOL) or not os.path.isfile(job.glb):
                self.report({"ERROR"}, f"Shatter: {job.message(code)}")
                return {"CANCELLED"}
            try:
                root, count, extended = self._bring_in(context, job)
            except Exception as e:  # the import failed: _bring_in removed what it made
                self.report({"ERROR"}, f"Shatter: importing {job.glb} failed: {e}")
                return {"CANCELLED"}
            if code != EXIT_OK:
                self.report({"WARNING"}, f"Shatter: {job.message(code)}")
            for w in job.process.warnings():
                self.report({"WARNING"}, f"Shatter: {w}")
            summary = root.get("shatter_summary", "")
            message = (f"Shatter: '{job.src_name}' in {count} pieces ({summary}; {job.drop_text}), in '{root.name}'"
                       f"{'; the scene now ends at frame %d' % context.scene.frame_end if extended else ''}. "
                       f"Report: {job.report_page}")
            self.report({"INFO"}, message)
            if not bpy.app.background and context.window is not None:
                results.show_popup(context, "Shatter", f"'{job.src_name}' in {count} pieces: {summary}",
                                   job.report_page, job.out_dir)
            return {"FINISHED"}
        finally:
            job.clean()

    def _bring_in(self, context, job):
        """Imports the run's .glb as the object's pieces; on failure the scene is as it was."""
        src = bpy.data.objects.get(job.src_name)
        if src is None:
            raise RunFailed(f"the object '{job.src_name}' was deleted while shatter ran "
                            f"(its pieces are in {job.glb})")
        scene, view_layer = context.scene, context.view_layer
        selected = [o for o in view_layer.objects if o.select_get()]
        active = view_layer.objects.active
        frame_end, hidden, hide_render = scene.frame_end, src.hide_get(), src.hide_render
        before = gltf_exchange.data_snapshot()
        try:
            parent = src.users_collection[0] if src.users_collection else scene.collection
            base = job.base if pieces.run_name(job.base) == job.base else pieces.run_name(src.name)
            collection = bpy.data.collections.new(f"{base}_shatter")
            parent.children.link(collection)
            made = gltf_exchange.import_glb(context, job.glb, collection)
            found, root, others = pieces.sort_imported(made)
            if not found or sorted(found) != list(range(len(found))):
                raise RunFailed(f"{job.glb} holds no pieces named piece_0 ... piece_N")
            if root is None:
                root = bpy.data.objects.new("shatter", None)
                collection.objects.link(root)
                for o in found.values():
                    o.parent = root
            pieces.remove_objects(others)
            pieces.arrange(base, found, root)
            frames = job.frames()
            last = pieces.retime(list(found.values()) + [root], frames, scene.frame_start)
            root["shatter_folder"] = job.out_dir
            root["shatter_report"] = job.report_page
            root["shatter_summary"] = summary_line(job.summary())
            extended = last > scene.frame_end
            if extended:
                scene.frame_end = int(math.ceil(last))
            src.hide_set(True)
            src.hide_render = True
            for o in view_layer.objects:
                o.select_set(False)
            root.select_set(True)
            for o in found.values():
                o.select_set(True)
            view_layer.objects.active = root
            return root, len(found), extended
        except Exception:
            gltf_exchange.remove_since(before)
            scene.frame_end = frame_end
            src.hide_set(hidden)
            src.hide_render = hide_render
            for o in view_layer.objects:
                o.select_set(o in selected)
            view_layer.objects.active = active
            raise


def menu_entry(self, context):
    self.layout.separator()
    self.layout.operator(OBJECT_OT_shatter.bl_idname, text="Shatter", icon="MOD_EXPLODE")
