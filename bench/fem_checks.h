// Checks of the continuum reference (bench/fem_solid.h) against theory, before it is used as a
// reference (docs/accuracy.md, "A continuum reference"). Each builds a box of Kuhn tets
// (bench/fem_box_mesh.h) with n cells across, so that the mesh convergence can be shown.
//
// - Cantilever, static: a tip load F on a clamped beam of length L and square side b deflects by
//   delta = F L^3 / (3 E I), I = b^4 / 12 (Euler-Bernoulli); Timoshenko adds F L / (kappa G A),
//   kappa = 10 (1 + nu) / (12 + 11 nu) for a rectangle (Cowper, J. Appl. Mech. 33, 1966).
// - Cantilever, first frequency: f1 = 1.875104^2 / (2 pi L^2) sqrt(E I / (rho A)) (Euler-Bernoulli;
//   e.g. Timoshenko, Young & Weaver, "Vibration Problems in Engineering", ch. 5). Measured twice:
//   as the lowest eigenvalue of K v = w^2 M v (inverse iteration), and from the tip's zero
//   crossings after the tip load is released (the time integrator's own period).
// - Bar, wave speed: a thin bar's longitudinal waves travel at c = sqrt(E / rho). One end is
//   pushed at v0 from rest; the far (free) end moves at 2 v0 once the front has arrived at L / c,
//   so at 2 L / c its displacement is 2 v0 L / c.
// - Energy: without damping, loads or fracture, kinetic + elastic energy stays constant under
//   the implicit midpoint rule: the cantilever's vibration, and a free bar tumbling at large
//   rotation (the corotational part; the midpoint rule conserves energy exactly only for a
//   linear force, so there the error should fall as h^2), compared with plain linear elasticity.
#pragma once

#include <cstdint>

#include "bench/fem_solid.h"

namespace shatter::fem {

struct CantileverGeometry {
    double length = 0.3;  // L (unit: m)
    double side = 0.03;   // b, square cross-section (unit: m)
    FemMaterial material;  // glass: 2500 kg/m^3, 70 GPa, nu 0.22
};

struct StaticResult {
    uint32_t cells = 0;  // across the side (10x as many along the length)
    size_t tets = 0, dofs = 0;
    double deflection = 0;     // mean tip deflection (unit: m)
    double euler_bernoulli = 0, timoshenko = 0;  // (unit: m)
    double seconds = 0;
};
StaticResult cantilever_static(const CantileverGeometry& g, uint32_t cells, double tip_force = 100);

struct FrequencyResult {
    uint32_t cells = 0;
    size_t tets = 0, dofs = 0;
    double modal = 0;           // lowest eigenfrequency (unit: Hz)
    double dynamic = 0;         // from the released tip's zero crossings (0 when not run) (unit: Hz)
    double euler_bernoulli = 0; // (unit: Hz)
    double energy_drift = 0;    // max |E(t) - E(0)| / E(0) over the dynamic run (kinetic + elastic)
    double seconds = 0;
};
// periods > 0 also integrates `periods` periods at `steps_per_period` midpoint steps.
FrequencyResult cantilever_frequency(const CantileverGeometry& g, uint32_t cells, int periods = 0,
                                     int steps_per_period = 100, bool corotational = true);

struct WaveResult {
    uint32_t cells = 0;
    size_t tets = 0;
    double arrival = 0;  // the front's arrival at the far end, 2 L / c - u(2 L / c) / (2 v0) (unit: s)
    double speed = 0;    // L / arrival (unit: m/s)
    double theory = 0;   // sqrt(E / rho) (unit: m/s)
    double seconds = 0;
};
// A bar length x side x side (default 0.3 x 0.01 m) with `cells` across, 30 x cells along; the
// step is the time a wave takes to cross a cell / steps_per_cell.
WaveResult bar_wave_speed(const FemMaterial& m, uint32_t cells, double steps_per_cell = 1, double length = 0.3,
                          double side = 0.01);

struct TumbleResult {
    double energy_drift = 0;    // max |E(t) - E(0)| / E(0) (kinetic + elastic)
    double max_elastic = 0;     // largest elastic energy over the run (unit: J)
    double initial_energy = 0;  // (unit: J)
    int steps = 0;
    double max_newton = 0;      // most Newton iterations a step took
};
// A free 0.1 x 0.02 x 0.02 m glass bar (2 x 2 x 10 cells), spinning at `spin` rad/s about its
// short axis z with a bending velocity on top, no gravity, for `turns` turns.
TumbleResult tumbling_bar(bool corotational, double spin = 200, double turns = 2, int steps_per_turn = 400);

}  // namespace shatter::fem

namespace shatter::fem {

// ---- interfaces (bench/fem_interfaces.h) ----

struct InterfaceStaticResult {
    uint32_t cells = 0;
    size_t ties = 0;
    double deflection_split = 0, deflection_whole = 0;  // tip deflection with and without the score (unit: m)
    double max_sigma = 0;       // largest tie tension under the tip load (unit: Pa)
    double break_load = 0;      // tip load at which the first tie reaches the strength (unit: N)
    double beam_theory = 0;     // strength I / ((b / 2) (L - x_score)) (unit: N)
};
// The cantilever of cantilever_static scored across at x_score (two pieces; x_score on a cell
// boundary), 100 N at the tip. Beam theory: the outer fibre at the score reaches the strength at
// F = strength I / ((b / 2) (L - x_score)).
InterfaceStaticResult scored_cantilever(const CantileverGeometry& g, uint32_t cells, double x_score,
                                        double strength = 40e6);

struct TensionBreakResult {
    double break_time = 0;       // first tie break (unit: s)
    double predicted = 0;        // strength L / (E v) (unit: s)
    size_t ties = 0, broken = 0;
    size_t fragments = 0;
    double sigma_spread = 0;     // (max - min) / mean tie tension one step before the break
    double seconds = 0;
};
// A 0.1 x 0.01 x 0.01 m glass bar (cells x cells x 10 cells) scored at mid-length, clamped at x = 0,
// its far end pulled at v (unit: m/s); midpoint steps of h, until a wave has crossed the bar twice
// after the first break. The stress is uniform: every tie should break within that time.
TensionBreakResult bar_tension_break(uint32_t cells, double v = 0.01, double h = 1e-5, double strength = 40e6);

}  // namespace shatter::fem
