// The study's beam scene (bench/study_scenes.cpp beam_case: a glass beam of two 0.3 x 0.03 x
// 0.03 m halves on the ground, pushed by a kinematic block between two posts) run by the
// continuum reference: the same geometry, glass's E = 70 GPa, nu = 0.22, rho = 2500 kg/m^3 and
// tensile (and shear) strength 40 MPa, the same posts, block keys, gravity and ground, with
// penalty contact (bench/fem_contact.h; each pair's friction as the rigid method has it,
// simulate/surface_pair.h: 0.35 on the ground, 0.45 on the posts and the block) and the score
// between the halves as interface ties (bench/fem_interfaces.h). The
// beam is n x n x 20n cubes of 6 Kuhn tets (n cells across).
#pragma once

#include <cstdint>
#include <vector>

#include "bench/fem_solid.h"

namespace shatter::fem {

struct PieceMotion {
    double time = 0;       // (unit: s)
    double kinetic = 0;    // every vertex's kinetic energy, vibration included (unit: J)
    double rigid = 0;      // the pieces' kinetic energy as rigid bodies: P^2 / 2M + L I^-1 L / 2 (unit: J)
    double spread = 0;     // the pieces' translational kinetic energy about their common centre of mass (unit: J)
};

// Pieces first to last of a split mesh (bench/fem_interfaces.h) as rigid bodies: their
// kinetic energy and translational kinetic energy about their common centre, from the vertices'
// momenta.
PieceMotion piece_motion(const FemSolid& solid, const std::vector<uint32_t>& vertex_piece, uint32_t first,
                         uint32_t last);

struct FemBeamResult {
    uint32_t cells = 0;
    size_t tets = 0, ties = 0, broken = 0, fragments = 0;
    double first_break = -1;  // (unit: s)
    double last_break = -1;   // (unit: s)
    PieceMotion at_01, at_05;  // 0.1 s and 0.5 s after the first break
    PieceMotion at_break;      // the step before the first break
    double elastic_at_break = 0;  // the solid's elastic energy the step before the first break (unit: J)
    double seconds = 0;           // wall time
    long steps = 0;
    long halved_steps = 0;       // steps Newton's method took as two halves (bench/fem_solid.h)
    long unconverged_steps = 0;  // steps taken unconverged at the shortest step
    bool complete = false;
};

// Runs from t_start (the block still 0.2 mm off the beam at 0.24 s) to 0.5 s after the first
// break, or to t_end when nothing breaks.
FemBeamResult run_fem_beam(uint32_t cells, double h, FemIntegrator integrator = FemIntegrator::BackwardEuler,
                           double t_start = 0.24, double t_end = 0.9);

}  // namespace shatter::fem
