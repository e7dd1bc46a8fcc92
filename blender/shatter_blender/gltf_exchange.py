"""The object out to glTF for shatter, and shatter's .glb back in as a collection of pieces, both
with Blender's own glTF add-on (io_scene_gltf2), leaving nothing behind when either fails.

Facts of io_scene_gltf2 this relies on (read in Blender 3.4's copy; 4.x keeps them):
 - the exporter writes selected objects only by their select_get() state, so the selection is
   set for the export and put back after it; a root node gets its object's world transform,
   in Blender units (the unit scale is not applied), Y up;
 - the importer turns Y up into Z up, divides lengths by the scene's unit scale, keys
   animation from frame 0 (at time x scene.render.fps in 3.4; pieces.retime does not rely on
   the rate), links what it makes into the active collection, selects it, and switches a scene
   rendered with neither Cycles nor Eevee to Eevee (put back here);
 - 3.4's importer uses numpy.bool, an alias numpy 1.24 removed: it is set to bool first, only
   where numpy lacks it.
"""

import bpy

# bpy.data collections the importer adds to; what it added is removed when the import fails.
DATA_KINDS = ("objects", "meshes", "materials", "images", "textures", "actions", "cameras", "lights",
              "node_groups", "collections")


def numpy_bool_guard():
    import warnings
    try:
        import numpy
    except ImportError:   # the glTF add-on then says what it lacks
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FutureWarning)   # numpy 1.24 warns that the name will return
        if not hasattr(numpy, "bool"):                   # 1.24 to 1.26 lack it; 2.x has it again
            numpy.bool = bool


def export_object(context, obj, path):
    """Writes `obj` alone (modifiers applied, its materials, world transform) to the .glb `path`.
    An object hidden in the view layer (an earlier run's original) is shown for the export: a
    hidden object cannot be selected. The view layer's selection, active object and the object's
    hidden state are as they were afterwards."""
    view_layer = context.view_layer
    selected = [o for o in view_layer.objects if o.select_get()]
    active = view_layer.objects.active
    hidden = obj.hide_get()
    try:
        obj.hide_set(False)
        for o in selected:
            o.select_set(False)
        obj.select_set(True)
        view_layer.objects.active = obj
        numpy_bool_guard()
        bpy.ops.export_scene.gltf(filepath=path, export_format="GLB", use_selection=True, export_apply=True,
                                  export_animations=False, export_cameras=False, export_lights=False,
                                  export_yup=True, export_extras=False)
    finally:
        obj.select_set(False)
        for o in selected:
            o.select_set(True)
        view_layer.objects.active = active
        obj.hide_set(hidden)


def _data_names():
    return {kind: set(getattr(bpy.data, kind).keys()) for kind in DATA_KINDS}


def _remove_new(before):
    """Removes every datablock made since `before` (_data_names()), objects first."""
    for kind in DATA_KINDS:
        data = getattr(bpy.data, kind)
        for name in set(data.keys()) - before[kind]:
            block = data.get(name)
            if block is not None:
                data.remove(block)


def _layer_collection(layer, collection):
    if layer.collection == collection:
        return layer
    for child in layer.children:
        found = _layer_collection(child, collection)
        if found:
            return found
    return None


def import_glb(context, path, collection):
    """Imports the .glb `path` into `collection` (linked in the view layer). Returns the objects it
    made. On any failure everything it made is removed and the exception passes on."""
    view_layer = context.view_layer
    scene = context.scene
    before = _data_names()
    engine = scene.render.engine
    active_layer = view_layer.active_layer_collection
    target = _layer_collection(view_layer.layer_collection, collection)
    if target is None:
        raise RuntimeError(f"collection '{collection.name}' is not in the view layer")
    try:
        view_layer.active_layer_collection = target
        numpy_bool_guard()
        result = bpy.ops.import_scene.gltf(filepath=path)
        if "FINISHED" not in result:
            raise RuntimeError(f"Blender's glTF importer did not read {path}")
        return [bpy.data.objects[n] for n in set(bpy.data.objects.keys()) - before["objects"]]
    except Exception:
        _remove_new(before)
        raise
    finally:
        view_layer.active_layer_collection = active_layer
        if scene.render.engine != engine:
            scene.render.engine = engine


def data_snapshot():
    """For undoing a half-done import step by step: see remove_since()."""
    return _data_names()


def remove_since(before):
    _remove_new(before)
