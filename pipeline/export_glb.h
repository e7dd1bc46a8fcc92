// The animation as a binary glTF (.glb) that Blender imports: one node per piece (and per
// kinematic body) with its mesh and material colour, and one animation whose channels key every
// node's translation and rotation at every recorded frame. Written with assimp's exporter.
// Pieces are coloured as render colours them with these settings (the defaults without): with
// the input's materials (colours = "input"), a glTF material per model material and face kind,
// the outer one with its base colour texture embedded (PNG or JPEG; other formats as PNG) and
// the surfaces' TEXCOORD_0, and the input's vertex colours as COLOR_0 (times the base colour,
// the outer material's factor then white).
// Given the render settings, it also holds the camera render draws with (node "camera", a glTF
// perspective camera of the same vertical field of view and aspect), keyed at every frame when
// it moves (render/camera_path.h), so that the file opens in a DCC tool with the movie's view.
#pragma once

#include <string>

#include "core/model.h"
#include "core/render_settings.h"
#include "core/trajectory.h"

namespace shatter {

// Throws Error(Io) when the file cannot be written (atomically: temporary name, then rename).
void export_glb(const Model& model, const Trajectory& trajectory, const std::string& glb_path,
                const RenderSettings* camera = nullptr);

}  // namespace shatter
