// The shot file: one human-written TOML file (comments allowed) that describes a shot. Sections:
//   [mesh]      the input mesh and how to repair it
//   [generate]  or, instead of [mesh], an object built from boxes (beam, plate, chain)
//   [prescore]  tetrahedralization, hollowing, partition, collision parts
//   [scene]     gravity, ground, [[scene.colliders]] (static), [[scene.kinematic]] (scripted)
//   [object]    where the fracturable object starts and how it moves
//   [material]  density, constraint stiffness, damping, strength, alpha, friction, restitution
//   [simulate]  duration, frame rate, substeps, iterations, break policy
//   [render]    image size, camera, lights, colours
// docs/shot.md documents every key with its unit, default and range. Unknown sections and keys
// are errors naming file:line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/generate_settings.h"
#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/settings.h"

namespace shatter {

struct Shot {
    std::string path;  // the shot file itself ("" when the shot came from flags alone)
    MeshSettings mesh;
    std::optional<GenerateSettings> generate;  // [generate]: set instead of [mesh]
    PrescoreSettings prescore;
    SceneSettings scene;
    ObjectSettings object;
    MaterialSettings material;
    // A shot's step is automatic unless it names one: it resolves a stiff joint's impact where a
    // fixed step would need thousands of steps a frame, and takes one step a block (1/480 s) where
    // nothing loads the joints (docs/physics.md, "The automatic step").
    SimulateSettings simulate{.auto_substeps = true};
    RenderSettings render;
};

// Reads and validates a shot file. The mesh path is made relative to the current directory.
// `overrides` are "SECTION.KEY=VALUE" settings that replace or add keys before validation, the
// value written as in the file (0.5, "12mm", [0, 1, 0], false; a bare word is taken as a string):
// `shatter run --set`, and the sweeps of a batch file. Errors in them name "--set SECTION.KEY=VALUE".
Shot load_shot(const std::string& path, const std::vector<std::string>& overrides = {});

// Applies `overrides` (as above) to a parsed shot table. Throws Error(Usage) naming the override.
void apply_shot_overrides(toml::table& root, const std::vector<std::string>& overrides);

// True when `path` names a shot file (by its extension, .toml) rather than a mesh.
bool is_shot_path(const std::string& path);

// The default shot, for a mesh given without a shot (`shatter run MESH`): assets/bunny.toml's
// settings without its mesh path, size and camera (a test keeps the two in step). The mesh gets
// the default size (core/settings.h) unless it has units, and the camera frames the animation.
extern const char* const kDefaultShot;

// The default shot on `mesh_path` (taken relative to the current folder), with `overrides`
// applied as load_shot applies them.
Shot default_shot_for_mesh(const std::string& mesh_path, const std::vector<std::string>& overrides = {});

// load_shot for a shot file (.toml), default_shot_for_mesh for anything else.
Shot load_shot_or_mesh(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace shatter
