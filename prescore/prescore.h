// prescore: a mesh in, pieces and constraints out. The public entry point of the stage.
//
//   load (assimp) -> size -> check -> [repair: alpha wrap] -> tetrahedralize (Mesh_3; the
//     resolution raised or thin walls thickened when parts are lost) -> [hollow] -> partition
//     (round-robin flood fill; slivers join their neighbours) -> constraints -> per piece:
//     surface, mass properties, collision parts
//
// prescore/adapt.h says how it adapts to real meshes, and how each choice is recorded.
//
// Each phase is its own file in prescore/; this file only chains them and times them.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/model.h"
#include "core/scene_settings.h"
#include "core/settings.h"
#include "core/shot.h"
#include "meshio/archive.h"
#include "meshio/mesh_load.h"
#include "prescore/adapt.h"
#include "prescore/mesh_check.h"

namespace shatter {

struct PrescoreReport {
    MeshCheck input;                 // the mesh as loaded
    bool repaired = false;           // alpha-wrapped
    MeshCheck tetrahedralized_from;  // the mesh Mesh_3 saw (the wrap when repaired)
    size_t tets_meshed = 0;          // tets before hollowing
    size_t tets_removed = 0;         // by hollowing
    size_t tets_restored = 0;        // put back by hollowing to keep the shell connected
    double hollow_thickness = 0;     // (unit: m) 0 when solid
    double scale = 1;                // metres per file unit, as chosen (prescore/adapt.h)
    double resolution = 0;           // cells per diagonal, as used
    AutoChoices choices;             // what prescore chose for this mesh, and why
    TriangleMesh surface;            // the closed surface the tets were made from (the input, its wrap or thickened wrap)
    size_t render_surfaces = 0;      // pieces given a render surface (fell back ones included)
    size_t render_fell_back = 0;     // of those, pieces on their tet surface
    size_t render_triangles = 0;     // triangles of every render surface
    nlohmann::ordered_json impact;   // seeds = "impact": the pre-pass's contacts and the grading (else null)
    std::vector<std::pair<std::string, double>> phase_seconds;  // in order
};

// The object's mesh as prescore takes it, before any check: unpacked first when it comes in an
// archive (.zip, .7z, .rar, tar; meshio/archive.h; the mesh chosen in it noted in `choices`), read
// (meshio/mesh_load.h), its coordinates' rounding warned and a size out of reach refused, turned to
// stand when the file is z-up ([mesh] up; noted in `choices`), and sized to metres (choose_scale).
// `shatter info MESH` describes the same mesh.
struct InputMesh {
    LoadedMesh loaded;  // its coordinates in metres
    double scale = 1;   // metres per file unit
    bool turned = false;  // read z-up and stood up
    std::string path;     // the mesh file read: the settings' path, or the file chosen in its archive
    std::shared_ptr<const MeshArchive> archive;  // the unpacked archive, kept while its files are read
};
InputMesh read_input_mesh(const MeshSettings& settings, AutoChoices& choices);

// The scene the object will fly in, for seeds = "impact" (prescore/impact.h).
struct FlightScene {
    const SceneSettings& scene;
    const ObjectSettings& object;
    const MaterialSettings& material;  // its strength and density: impact_ratio and impact_radius "auto"
};

// Runs every phase; throws Error for bad input (unreadable mesh, mesh that cannot be
// tetrahedralized and may not be repaired, more pieces than tets, ...). seeds = "impact" needs
// `flight`; without it the seeds are uniform.
Model prescore(const MeshSettings& mesh, const PrescoreSettings& settings, PrescoreReport* report,
               const FlightScene* flight = nullptr);

// The shot's model: built from boxes when the shot has [generate] (scenes/paper_scenes.h; no
// mesh, no tets, report->phase_seconds holds "generate"), else prescore(shot.mesh,
// shot.prescore, report, the shot's scene and object). Throws Error(BadInput) naming the shot when it has neither.
Model prescore_shot(const Shot& shot, PrescoreReport* report);

// The stage's files: the model at `model_path` and, beside it, STEM.pieces.ply (the pieces as one
// coloured PLY for a quick look; prescore/pieces_ply.h), each written atomically. Returns the
// PLY's path.
std::string save_prescore_outputs(const Model& model, const std::string& model_path);

}  // namespace shatter
