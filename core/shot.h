// The shot file: one human-written TOML file (comments allowed) that describes a shot. Sections:
//   [mesh]      the input mesh and how to repair it
//   [prescore]  tetrahedralization, hollowing, partition, collision parts
// (scene, simulate and render sections arrive with their stages). docs/shot.md documents every
// key with its unit, default and range. Unknown sections and keys are errors naming file:line.
#pragma once

#include <string>

#include "core/settings.h"

namespace shatter {

struct Shot {
    std::string path;  // the shot file itself ("" when the shot came from flags alone)
    MeshSettings mesh;
    PrescoreSettings prescore;
};

// Reads and validates a shot file. The mesh path is made relative to the current directory.
Shot load_shot(const std::string& path);

// True when `path` names a shot file (by its extension, .toml) rather than a mesh.
bool is_shot_path(const std::string& path);

}  // namespace shatter
