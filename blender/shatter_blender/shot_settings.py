"""The operator's options as `shatter run --set` overrides of the default shot (docs/shot.md).

No bpy here: the operator measures the scene (scene_measure.py) and passes plain numbers.

How the object keeps its place: the glTF that Blender writes holds the object with its world
transform, in Blender units, Y up. shatter takes it at `mesh.scale` metres per unit (the scene's
unit scale) with its model frame at the world's origin (`object.place = "origin"`, position
0), so that shatter's world is Blender's world in metres, Y up; the .glb it writes is in that
frame too, and the import puts every piece where the trajectory puts it. The drop is made by
moving the ground (`scene.ground_height`), never the object.
"""

import math

# docs/shot.md, "Material presets"; "DEFAULT" keeps the default shot's own material (a weak
# cast: stiffness 3e9 N/m^3, strength 20 kPa, the one `shatter run MESH` uses).
PRESETS = ("glass", "porcelain", "ceramic_tile", "gypsum_plaster", "concrete", "stone", "ice", "weak_cast")

# Stage names of `shatter run --stages` (docs/pipeline.md): without the movie, no frames are drawn.
STAGES_WITHOUT_MOVIE = ("prescore", "simulate", "plot", "export", "report")


class BadOption(ValueError):
    """An option outside what shatter accepts; the message names it, its value and the fix."""


def _number(x):
    """A float as TOML reads it: shortest round trip, never NaN or infinite."""
    return repr(float(x))


def shot_overrides(pieces, preset, alpha, seed, ground_height_m, fps, frames, metres_per_unit):
    """The (key, value) pairs for `shatter run --set`, in a stable order.

    pieces: count (prescore.pieces); preset: "DEFAULT" or a name of PRESETS; alpha: 1
    (material.alpha); seed: prescore.seed and simulate.seed; ground_height_m: the ground plane's
    height in metres, in shatter's Y-up world; fps: frames per second (simulate.fps, the
    scene's); frames: 0 for "auto" (until the pieces rest), else the frame count, frame 0 at
    t = 0 (simulate.duration = (frames - 1) / fps); metres_per_unit: the scene's unit scale.
    """
    if preset != "DEFAULT" and preset not in PRESETS:
        raise BadOption(f"material preset '{preset}' is not one shatter knows (fix: one of DEFAULT, {', '.join(PRESETS)})")
    if frames == 1:
        raise BadOption("frames = 1: a fracture needs at least two frames (fix: 0 for auto, until the pieces rest, or 2 or more)")
    if not (1.0 <= fps <= 1000.0):
        raise BadOption(f"the scene's frame rate {fps:g} fps is outside shatter's 1 to 1000 fps (fix: Output Properties > Frame Rate)")
    if not (1e-9 <= metres_per_unit <= 1e9) or not math.isfinite(metres_per_unit):
        raise BadOption(f"the scene's unit scale {metres_per_unit:g} m per unit is outside 1e-9 to 1e9 "
                        "(fix: Scene Properties > Units > Unit Scale)")
    out = [
        ("mesh.scale", _number(metres_per_unit)),
        ("mesh.up", "y"),
        ("object.place", "origin"),
        ("object.position", "[0, 0, 0]"),
        ("scene.ground", "true"),
        ("scene.ground_height", _number(ground_height_m)),
        ("prescore.pieces", str(int(pieces))),
        ("prescore.seed", str(int(seed))),
        ("simulate.seed", str(int(seed))),
        ("material.alpha", _number(alpha)),
        ("simulate.fps", _number(fps)),
    ]
    if preset != "DEFAULT":
        out.append(("material.preset", preset))
    if frames:
        out.append(("simulate.duration", _number((frames - 1) / fps)))
    return out
