// The animation as a binary glTF (.glb) that Blender imports: one node per piece (and per
// kinematic body) with its mesh and material colour, and one animation whose channels key every
// node's translation and rotation at every recorded frame. Written with assimp's exporter.
#pragma once

#include <string>

#include "core/model.h"
#include "core/trajectory.h"

namespace shatter {

// Throws Error(Io) when the file cannot be written (atomically: temporary name, then rename).
void export_glb(const Model& model, const Trajectory& trajectory, const std::string& glb_path);

}  // namespace shatter
