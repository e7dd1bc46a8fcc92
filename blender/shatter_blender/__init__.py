"""Shatter for Blender: Object > Shatter fractures the active mesh object with the `shatter`
program and brings its pieces back, animated, in the object's place (docs/blender.md).

  operator.py         the operator: start, wait (modal or in place), finish
  shot_settings.py    its options as `shatter run --set` overrides (no bpy)
  scene_measure.py    the object's lowest point, the scene's floor, frame rate, unit scale
  shatter_process.py  `shatter run` as a child process: progress, cancel, errors (no bpy)
  gltf_exchange.py    the object out and the pieces in, with Blender's glTF add-on
  pieces.py           the imported pieces named, retimed, the camera dropped
  results.py          the buttons that open the run's report page and folder
  preferences.py      where the shatter binary is, where runs go
"""

bl_info = {
    "name": "Shatter",
    "author": "shatter developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Object > Shatter",
    "description": "Fracture the selected object into animated pieces with shatter (energized rigid body fracture)",
    "category": "Object",
}

import bpy  # noqa: E402

from . import operator, preferences, results  # noqa: E402

CLASSES = (preferences.ShatterPreferences, operator.OBJECT_OT_shatter) + results.CLASSES


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object.append(operator.menu_entry)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(operator.menu_entry)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
