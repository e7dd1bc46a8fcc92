// A shot's scene run by the continuum reference (bench/fem_solid.h): the model's own tets split
// along its pieces (bench/fem_interfaces.h: one tie per interface vertex, where the rigid method
// has one point constraint), placed where the shot places the object, with the shot's gravity,
// ground and static colliders (spheres and axis-aligned boxes) as penalty contacts
// (bench/fem_contact.h). Models without tets (the generated box scenes: the plate) are meshed
// as a grid of Kuhn tets over their boxes, `box_cells` cells across a box's shortest side; a
// prescored model's tets can be refined by regular 1:8 subdivision (each edge halved), which
// keeps the pieces and their interfaces and halves the tet size, for a check of convergence.
//
// The object starts at rest and falls freely (no stress in a uniformly accelerated solid), so
// the run starts `lead` metres of fall before its first vertex would touch an obstacle, with the
// free fall's position and velocity. Steps of h until `fine_window` seconds after the first
// tie breaks, of h_after from then on, to `after` seconds after the first break (or, without a
// break, `no_break_wait` seconds after the start). Backward Euler: it damps the pieces'
// vibration (docs/accuracy.md section 8). The reference has no self-contact: pieces that part do
// not touch each other again.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bench/fem_beam.h"
#include "bench/fem_interfaces.h"
#include "core/model.h"
#include "core/scene_settings.h"

namespace shatter::fem {

struct FemSceneSettings {
    FemMaterial material;        // density (the model's), Young's modulus, Poisson's ratio
    Strength strength;           // the shot's tensile strength, for shear as well
    double friction = 0.5;       // the object's; a contact's is the pair's (simulate/surface_pair.h)
    uint32_t box_cells = 3;      // box models: cells across a box's shortest side
    uint32_t refine = 0;         // tet models: 1:8 subdivisions
    double h = 2e-5, h_after = 1e-4;  // (unit: s)
    double fine_window = 0.01;   // (unit: s)
    double after = 0.5;          // (unit: s)
    double lead = 0.002;         // (unit: m) of fall before the first contact
    double no_break_wait = 0.3;  // (unit: s)
    double contact_stiffness = 1e8;  // per vertex (unit: N/m)
    bool progress = false;       // a line to stderr every 1,000 steps
};

// Splits every tet into 8 (corners and the inner octahedron cut along one diagonal); tet_piece
// is carried over. Edge midpoints are shared, so tets stay face to face.
void refine_tets(TetMesh& mesh, std::vector<uint32_t>& tet_piece);

// A box model's (one box per piece, core/model.h's pieces with box surfaces) tets: a grid over
// their bounding box whose cells lie in one box each, `cells` across the shortest box side.
void box_model_tets(const Model& model, uint32_t cells, TetMesh& mesh, std::vector<uint32_t>& tet_piece);

// The length a model's stiffness per area stands for (E = stiffness x l): a box model's shortest
// piece side, a prescored model's mean tet edge.
double stiffness_length(const Model& model);

// The reference's settings for an object of `model` with the shot's `material`: the shot's density
// (else the model's), Young's modulus the shot's, else its stiffness x stiffness_length, Poisson's
// ratio `poisson` (the rigid model has none), the shot's strength for tension and shear, its
// friction; plate-like box models h = 1e-5 s (the 7 GPa plaster's tets), others 1e-4 s.
FemSceneSettings scene_settings(const Model& model, const MaterialSettings& material, double poisson = 0.2);

struct FemSceneResult {
    size_t tets = 0, vertices = 0, ties = 0, broken = 0, fragments = 0, pieces = 0;
    double start_time = 0;        // the run's start in the shot's time (unit: s)
    double contact_time = 0;      // when the free fall would first touch an obstacle (unit: s)
    double first_break = -1;      // the first tie's, in the shot's time (unit: s)
    double last_break = -1;       // (unit: s)
    // The touching piece pairs, and those whose every tie broke (pairs (a, b), a < b).
    std::vector<std::pair<uint32_t, uint32_t>> pairs, separated;
    PieceMotion at_01, at_05;     // every piece, 0.1 s and `after` s after the first break
    double elastic_at_break = 0;  // the step before the first break (unit: J)
    double impact_energy = 0;     // the free fall's kinetic energy at first contact (unit: J)
    double seconds = 0;           // wall time
    long steps = 0, halved_steps = 0, unconverged_steps = 0;
    bool complete = false;
};

FemSceneResult run_fem_scene(const Model& model, const SceneSettings& scene, const ObjectSettings& object,
                             const FemSceneSettings& s);

}  // namespace shatter::fem
