"""The add-on's preferences: where the shatter binary is, and where runs go."""

import os
import tempfile

import bpy

ADDON = __package__


class ShatterPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    shatter_binary: bpy.props.StringProperty(
        name="shatter binary",
        description="The shatter program (build/bin/shatter after `make`); empty: `shatter` on PATH",
        subtype="FILE_PATH", default="")
    output_folder: bpy.props.StringProperty(
        name="Runs folder",
        description="Where each run's folder goes (report.html, the movie, the .glb); empty: a 'shatter' folder "
                    "beside the saved .blend file, or the system's temporary folder for an unsaved file",
        subtype="DIR_PATH", default="")

    def draw(self, context):
        self.layout.prop(self, "shatter_binary")
        self.layout.prop(self, "output_folder")


def preferences(context):
    return context.preferences.addons[ADDON].preferences


def runs_folder(context):
    """The folder that holds one folder per run, made absolute."""
    chosen = preferences(context).output_folder
    if chosen:
        return os.path.abspath(bpy.path.abspath(chosen))
    if bpy.data.filepath:
        return os.path.join(os.path.dirname(bpy.data.filepath), "shatter")
    return os.path.join(tempfile.gettempdir(), "shatter-blender")
