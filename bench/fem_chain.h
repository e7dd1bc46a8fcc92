// The chain of assets/chain.toml (bench/study_scenes.cpp chain_case: ten 3 x 1 x 1 cm porcelain
// links lying on the ground in a line between two 5 cm end cubes, which stand still until 0.3 s
// and are then driven apart at 1.11 cm/s each) run by the continuum reference: E = 70 GPa,
// nu = 0.22, rho = 2400 kg/m^3, tensile (and shear) strength 40 MPa, ground friction 0.5. The
// links are one box of n x n x 30n cubes of 6 Kuhn tets (n cells across), cut into pieces at the
// joints: each joint is its 1 x 1 cm face, tied by (n + 1)^2 ties (bench/fem_interfaces.h). The
// end cubes are driven, that is rigid: each is a slab one cell thick on the chain's section, every
// vertex of it driven, tied to its link like a joint (the rigid method's joint there is the
// 1 x 1 cm overlap of the cube's face and the link's). Nothing else touches: the links meet the
// ground, not each other nor the cubes (the reference has no self-contact).
#pragma once

#include <cstdint>
#include <vector>

#include "bench/fem_beam.h"

namespace shatter::fem {

struct FemChainResult {
    uint32_t cells = 0;
    size_t tets = 0, ties = 0, broken = 0, fragments = 0;
    double first_break = -1;  // a tie's (unit: s)
    double first_separation = -1;  // the first joint's whose ties all broke: the rigid method's break (unit: s)
    double last_break = -1;   // (unit: s)
    double predicted_break = 0;  // quasi-static: 0.3 s + strength x (10 links' length) / (E x 2 v) (unit: s)
    std::vector<int> joints_broken;  // joints (0: left cube / link 1, ..., 10: link 10 / right cube) whose ties all broke
    std::vector<double> joint_break_time;  // per joint: when its last tie broke, -1 if it holds
    // The links' (pieces 1 to 10) kinetic energy as rigid bodies and translational kinetic energy
    // about their common centre 0.1 s and 0.5 s after the first break (or at the run's end).
    PieceMotion at_01, at_05;
    double elastic_at_break = 0;  // the links' elastic energy the step before the first break (unit: J)
    // The middle joint's (5) normal force, the sum of its ties' (bench/fem_interfaces.h), the step
    // before the first break, and the quasi-static force of a uniform bar of the ten links then:
    // E A x (the ends' separation) / (10 links' length) (unit: N).
    double middle_force_at_break = 0, middle_force_predicted = 0;
    double seconds = 0;           // wall time
    long steps = 0, halved_steps = 0, unconverged_steps = 0;
    bool complete = false;
};

// From 0.3 s (the ends start to move) to `after` s after the first break (at most t_end), with
// steps of h up to 10 ms after the first break and of h_after from then on.
FemChainResult run_fem_chain(uint32_t cells, double h, double h_after, double after = 0.5, double t_end = 1.5);

}  // namespace shatter::fem
