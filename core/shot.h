// The shot file: one human-written TOML file (comments allowed) that describes a shot. Sections:
//   [mesh]      the input mesh and how to repair it
//   [prescore]  tetrahedralization, hollowing, partition, collision parts
//   [scene]     gravity, ground, [[scene.colliders]] (static), [[scene.kinematic]] (scripted)
//   [object]    where the fracturable object starts and how it moves
//   [material]  density, constraint stiffness, damping, strength, alpha, friction, restitution
//   [simulate]  duration, frame rate, substeps, iterations, break policy
//   [render]    image size, camera, lights, colours
// docs/shot.md documents every key with its unit, default and range. Unknown sections and keys
// are errors naming file:line.
#pragma once

#include <string>

#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/settings.h"

namespace shatter {

struct Shot {
    std::string path;  // the shot file itself ("" when the shot came from flags alone)
    MeshSettings mesh;
    PrescoreSettings prescore;
    SceneSettings scene;
    ObjectSettings object;
    MaterialSettings material;
    SimulateSettings simulate;
    RenderSettings render;
};

// Reads and validates a shot file. The mesh path is made relative to the current directory.
Shot load_shot(const std::string& path);

// True when `path` names a shot file (by its extension, .toml) rather than a mesh.
bool is_shot_path(const std::string& path);

}  // namespace shatter
