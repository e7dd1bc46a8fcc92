// The sections of the study program (bench/study.cpp), each writing one CSV into Options::out.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "bench/study.h"

namespace shatter::study {

struct Options {
    bool quick = false;
    bool precision_only = false;  // the float build: only the substeps sweeps and the identities
    std::string out = "bench/results/study";
    std::string refs = "/tmp/shatter-study-refs";  // reference trajectories (the float build reads them)
    std::vector<std::string> scenes;               // for sweeps, methods and speed
    std::vector<std::string> shots;                // for smallest: assets/<shot>.toml
    bool render = true;                            // time rendering in the speed section
};

// The numbers `--quick` checks (docs/accuracy.md, "Headline numbers").
struct Headlines {
    double energy_identity = NAN;       // rig, energized, exact energy: max relative error per break
    size_t energy_identity_breaks = 0;
    double stiffness_identity = NAN;    // stiffness rig, 1e10 N/m^3, 8 substeps, 20 iterations
    std::vector<std::pair<double, double>> rig_substeps_error;  // (substeps, trajectory error m)
    double plain_injected = NAN;        // rig, plain: energy injected (must be 0)
    double energized_books = NAN;       // rig, energized: (injected - alpha E) / alpha E
    double paper_books = NAN;           // rig, paper literal: the same
    size_t stable_plain = 0, cells_plain = 0;          // stability map h x stiffness, inside the CFM guard
    size_t stable_energized = 0, cells_energized = 0;
    // mass x alpha map, over the cells with alpha > 0 where plain breaking (alpha = 0 at that mass
    // ratio) is stable: how many there are, and in how many each energized method is stable too.
    size_t plain_stable_cells = 0;
    std::vector<std::pair<std::string, size_t>> stable_where_plain;  // (method, cells)
    // mass x alpha map, mass ratios 100 and 1,000, alpha 0 to 10: cells where energized with direct
    // joints (simulate/bullet_solver.h) is stable, of all such cells.
    size_t direct_stable_heavy = 0, direct_cells_heavy = 0;
    // mass x alpha map, every mass ratio, alpha 0 to 10: cells where the shipped method with the
    // shipped joints ("auto": direct up to 100 pieces) is stable, of all such cells.
    size_t shipped_stable = 0, shipped_cells = 0;
    // smallest: per shot, the largest deviation / tolerance of the shot as shipped and of the
    // chosen model (quick: the shipped one), against the finest model (<= 1 passes).
    struct Smallest {
        std::string shot;
        double shipped_worst, chosen_worst;
        bool chosen_is_shipped;
    };
    std::vector<Smallest> smallest;
    // reference: the chain (assets/chain.toml) up to its first break on the continuum reference
    // (2 cells across): when its first joint separated, the quasi-static prediction of that, the
    // rigid method's first break as shipped (unit: s); the middle joint's force the step before the
    // first tie broke over a uniform bar's (unit: 1).
    double chain_fem_break = NAN, chain_predicted_break = NAN, chain_rigid_break = NAN;
    double chain_middle_force_ratio = NAN;
    size_t chain_fem_joints = 0;  // joints whose ties all broke
    // reference: the plate (assets/plate.toml) to its first break: the free fall's first contact
    // with the sphere, the first tie's break on the continuum reference (2 cells across a cube, step
    // plate_step), the same in the committed bench/results/study/fem_plate.csv's 2-cell row, the rigid method's
    // first break as shipped (unit: s).
    double plate_contact = NAN, plate_fem_break = NAN, plate_committed_break = NAN, plate_rigid_break = NAN;
    double plate_step = NAN;
};

bool section_identities(const Options& opt, Headlines& h);
bool section_sweeps(const Options& opt, Headlines& h);
bool section_methods(const Options& opt, Headlines& h);
bool section_stability(const Options& opt, Headlines& h);
bool section_continuum(const Options& opt, Headlines& h);
bool section_speed(const Options& opt, Headlines& h);
bool section_smallest(const Options& opt, Headlines& h);
bool section_reference(const Options& opt, Headlines& h);
bool section_seeds(const Options& opt, Headlines& h);

}  // namespace shatter::study
