// Pre-scored interfaces for the continuum reference (bench/fem_solid.h): a tet mesh split into
// pieces (prescore's tet_piece) gets one copy of every interface vertex per piece. The copies
// move as one vertex (shared degrees of freedom) while their interface holds, so the intact
// solid is exactly the unsplit one. Fracture happens only along these interfaces, as in the rigid
// method, for a like-for-like comparison: a tie (one interface vertex between two pieces, the
// counterpart of a rigid point constraint) breaks when the traction it carries exceeds the
// material's strength:
//
//   normal traction  sigma = -F . n / A > tensile strength   (tension)
//   shear traction   tau = |F - (F . n) n| / A > shear strength
//
// F is the force piece b's copy receives from piece a's, n the interface normal from a to b and
// A the tie's share of the interface area (a third of each shared face at the vertex, as
// prescore shares the area among constraints). This is a cohesive "tie-break" model of brittle
// fracture with the strength criterion of Rankine (maximum normal stress) and a maximum shear
// stress cut-off; it is not a fracture-mechanics (energy release rate) criterion.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "bench/fem_solid.h"

namespace shatter::fem {

struct Tie {
    uint32_t vertex = 0;            // the original (unsplit) vertex
    uint32_t piece_a = 0, piece_b = 0;  // piece_a < piece_b
    uint32_t copy_a = 0, copy_b = 0;    // the two pieces' copies in the split mesh
    double area = 0;                // (unit: m^2)
    Vec3 normal = Vec3::Zero();     // unit, from piece a into piece b
    bool broken = false;
    double break_time = -1;         // (unit: s)
};

struct SplitMesh {
    TetMesh mesh;                    // tets re-indexed onto their piece's copies
    std::vector<uint32_t> vertex_piece;  // per split vertex
    std::vector<uint32_t> original;      // per split vertex: the vertex it copies
    std::vector<Tie> ties;               // sorted by (piece_a, piece_b, vertex)
    uint32_t pieces = 0;
};

// Splits `mesh` along the faces whose two tets lie in different pieces.
SplitMesh split_pieces(const TetMesh& mesh, const std::vector<uint32_t>& tet_piece);

struct Strength {
    double tensile = 40e6;  // (unit: Pa) glass's modulus of rupture (docs/scenes.md)
    double shear = 40e6;    // (unit: Pa)
};

// The ties' tractions from the solid's last step and the breaking of the overloaded ones.
class Interfaces {
public:
    explicit Interfaces(SplitMesh split) : s_(std::move(split)) {}
    const SplitMesh& split() const { return s_; }
    std::vector<Tie>& ties() { return s_.ties; }

    // Joins every intact tie's copies in `solid` (call once after building it on split().mesh).
    void apply(FemSolid& solid) const;
    // The normal and shear traction of tie i after the solid's last step (unit: Pa).
    void traction(const FemSolid& solid, size_t i, double& sigma, double& tau) const;
    // Breaks every intact tie whose traction exceeds `strength`; re-joins the solid's copies when
    // one did. Returns how many broke.
    size_t break_overloaded(FemSolid& solid, const Strength& strength);
    // Groups of pieces the intact ties still join (pieces joined to nothing count one each).
    size_t fragments() const;
    // The largest tensile and shear traction over intact ties after the last step (unit: Pa).
    double max_sigma = 0, max_tau = 0;

private:
    SplitMesh s_;
};

// The closing tallies every reference run reports (FemBeamResult, FemChainResult, FemSceneResult):
// ties broken, fragments, the steps Newton's method halved or left unconverged, and the wall time
// since `start`.
template <class Result>
void tally_run(const Interfaces& in, const FemSolid& solid, std::chrono::steady_clock::time_point start, Result& r) {
    for (const Tie& t : in.split().ties) r.broken += t.broken;
    r.fragments = in.fragments();
    r.halved_steps = solid.halved_steps();
    r.unconverged_steps = solid.unconverged_steps();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace shatter::fem
