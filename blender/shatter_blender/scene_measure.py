"""What the operator reads from the scene: the object's lowest point, where the ground is, the
frame rate and the unit scale. Blender is Z up; shatter's world is Y up (the glTF's), so a
height in Blender (z, in Blender units) is a height in shatter (y, in metres) times the unit
scale.
"""

import mathutils


def lowest_point(obj, depsgraph):
    """The lowest world z of the object's evaluated mesh (modifiers applied), in Blender units."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        m = evaluated.matrix_world
        return min((m @ v.co).z for v in mesh.vertices) if mesh.vertices else None
    finally:
        evaluated.to_mesh_clear()


def top_of(obj):
    """The highest world z of an object's bounding box, in Blender units."""
    return max((obj.matrix_world @ mathutils.Vector(c)).z for c in obj.bound_box)


def scene_floor(context, obj, bottom):
    """The scene's lowest surface below the object: the lowest top of the other visible mesh
    objects whose top is at or below the object's lowest point (a floor plane, a ground slab);
    with none, z = 0 (Blender's floor grid) when the object is above it, else the object's own
    lowest point (it then rests where it is). Returns (z, what) with what naming the surface.
    """
    best, name = None, None
    for other in context.view_layer.objects:
        if other == obj or other.type != "MESH" or not other.visible_get():
            continue
        top = top_of(other)
        if top <= bottom + 1e-9 and (best is None or top < best):
            best, name = top, other.name
    if best is not None:
        return best, f"the top of '{name}'"
    if bottom >= 0.0:
        return 0.0, "the floor grid (z = 0)"
    return bottom, "the object's lowest point (nothing below it)"


def frame_rate(scene):
    """The scene's frames per second (fps / fps_base: 29.97 for NTSC)."""
    return scene.render.fps / scene.render.fps_base


def metres_per_unit(scene):
    """Metres per Blender unit: the unit scale (1 unless the scene says otherwise)."""
    return scene.unit_settings.scale_length
