"""shatter's imported .glb made into the run's result: one empty holding the pieces, each piece
named after the object and numbered as shatter numbers it, its keys on the scene's frames.

The .glb (pipeline/export_glb.h) holds nodes "piece_0" ... "piece_{N-1}", their origins at the
pieces' centres of mass and keyed at every recorded frame, under a root "shatter", and a
"camera" node (the movie's camera): the camera is not kept, the scene has its own.
"""

import re

import bpy

PIECE_NAME = re.compile(r"^piece_(\d+)(?:\.\d+)?$")   # ".001": Blender's suffix for a name already taken
SNAP = 1e-3   # frames: a key this close to a whole frame is put on it


def sort_imported(objects):
    """(pieces by shatter's index, the root empty or None, everything else) of the import."""
    pieces, root, others = {}, None, []
    for o in objects:
        m = PIECE_NAME.match(o.name)
        if m and o.type == "MESH":
            pieces[int(m.group(1))] = o
        elif o.type == "EMPTY" and root is None and o.parent is None and re.match(r"^shatter(\.\d+)?$", o.name):
            root = o
        else:
            others.append(o)
    return pieces, root, others


def remove_objects(objects):
    """Removes objects and the data, actions and animation that only they use."""
    for o in objects:
        data = o.data
        action = o.animation_data.action if o.animation_data else None
        bpy.data.objects.remove(o)
        if data is not None and data.users == 0:
            for kind in ("cameras", "meshes", "lights"):
                blocks = getattr(bpy.data, kind)
                if blocks.get(data.name) == data:
                    blocks.remove(data)
                    break
        if action is not None and action.users == 0:
            bpy.data.actions.remove(action)


def retime(objects, frames, start):
    """Puts each object's keys on the scene's frames: shatter keys every recorded frame, frame k at
    k / fps, and the importer places a key at its time x its own frame rate (3.4: render.fps,
    without fps_base), so key times are scaled to make the last recorded frame's key land on
    start + frames - 1, whatever rate the importer used, and snapped to whole frames. Drops the
    importer's muted NLA stash of the same action (its strip would keep the old range). Returns
    the last frame."""
    actions = []
    for o in objects:
        ad = o.animation_data
        if ad is None:
            continue
        while ad.nla_tracks:
            ad.nla_tracks.remove(ad.nla_tracks[0])
        if ad.action is not None:
            actions.append(ad.action)
    imported_last = max((kp.co.x for a in actions for fc in a.fcurves for kp in fc.keyframe_points), default=0.0)
    scale = (frames - 1) / imported_last if imported_last > 0 and frames > 1 else 1.0
    for action in actions:
        for fc in action.fcurves:
            for kp in fc.keyframe_points:
                x = start + kp.co.x * scale
                if abs(x - round(x)) < SNAP:
                    x = float(round(x))
                shift = x - kp.co.x
                kp.co.x = x
                kp.handle_left.x += shift
                kp.handle_right.x += shift
            fc.update()
    return start + frames - 1


def run_name(src_name, busy=lambda base: False):
    """The name of a new run of `src_name`: "NAME", or "NAME.001", ... when an earlier run of it
    has the collection or the empty "NAME_shatter" already, or busy(name) says a run has it."""
    base, n = src_name, 0
    while f"{base}_shatter" in bpy.data.objects or f"{base}_shatter" in bpy.data.collections or busy(base):
        n += 1
        base = f"{src_name}.{n:03d}"
    return base


def _rename(block, name, blocks):
    # Blender gives a name that is taken to the block renamed and a ".001" to the other: another
    # object would be renamed. So a taken name gets a free suffix here first.
    free, n = name, 0
    while blocks.get(free) not in (None, block):
        n += 1
        free = f"{name}.{n:03d}"
    block.name = free


def arrange(base, pieces, root):
    """Names the root "BASE_shatter" and the pieces "BASE_piece_I", marks each piece with its index."""
    _rename(root, f"{base}_shatter", bpy.data.objects)
    for i, o in sorted(pieces.items()):
        _rename(o, f"{base}_piece_{i}", bpy.data.objects)
        _rename(o.data, o.name, bpy.data.meshes)
        o["shatter_piece"] = i
