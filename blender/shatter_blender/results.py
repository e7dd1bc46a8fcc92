"""A run's result in Blender: the buttons that open its report page and its folder, in a popup when
the run ends and in Object Properties > Shatter for any of its pieces afterwards.

The run's paths are kept on the pieces' root object (custom properties shatter_report and
shatter_folder), so that they survive saving the .blend file.
"""

import os

import bpy


def run_root(obj):
    """The root object of a shatter run that `obj` belongs to, or None."""
    while obj is not None:
        if "shatter_folder" in obj:
            return obj
        obj = obj.parent
    return None


class SHATTER_OT_open_path(bpy.types.Operator):
    """Open a shatter run's report page or folder with the system's default program"""
    bl_idname = "shatter.open_path"
    bl_label = "Open"
    bl_options = {"INTERNAL"}

    path: bpy.props.StringProperty(subtype="FILE_PATH")

    def execute(self, context):
        if not os.path.exists(self.path):
            self.report({"ERROR"}, f"{self.path} is not there any more (fix: run Object > Shatter again)")
            return {"CANCELLED"}
        bpy.ops.wm.path_open(filepath=self.path)
        return {"FINISHED"}


def draw_links(layout, report, folder):
    row = layout.row(align=True)
    if report and os.path.exists(report):
        row.operator(SHATTER_OT_open_path.bl_idname, text="Open report", icon="URL").path = report
    row.operator(SHATTER_OT_open_path.bl_idname, text="Open run folder", icon="FILE_FOLDER").path = folder


def show_popup(context, title, message, report, folder):
    """The end of a run, with its links, where there is a window to show it in."""
    def draw(menu, _context):
        menu.layout.label(text=message)
        draw_links(menu.layout, report, folder)
    context.window_manager.popup_menu(draw, title=title, icon="MOD_EXPLODE")


class OBJECT_PT_shatter_run(bpy.types.Panel):
    bl_label = "Shatter"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return run_root(context.object) is not None

    def draw(self, context):
        root = run_root(context.object)
        layout = self.layout
        layout.label(text=root.get("shatter_summary", ""))
        layout.label(text=f"Folder: {root['shatter_folder']}")
        draw_links(layout, root.get("shatter_report", ""), root["shatter_folder"])


CLASSES = (SHATTER_OT_open_path, OBJECT_PT_shatter_run)
