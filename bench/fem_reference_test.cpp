// Tests of the continuum reference (bench/fem_solid.h) against the theory it must reproduce
// before the study uses it (bench/fem_checks.h; docs/accuracy.md, "A continuum reference"):
// beam theory for a cantilever's deflection and first frequency with the mesh convergence of
// linear tets, the trapezoidal rule's period, a bar's wave speed, energy conservation, and
// rigid motions that store no energy.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/fem_box_mesh.h"
#include "bench/fem_checks.h"
#include "bench/fem_contact.h"
#include "bench/fem_interfaces.h"
#include "bench/fem_scene.h"

using namespace shatter;
using namespace shatter::fem;

// Linear tets are too stiff in bending and converge from below, at about second order in the
// cell size; the limit is Timoshenko's deflection (shear adds 0.72% to Euler-Bernoulli's here).
TEST(FemReference, CantileverDeflectionConvergesToBeamTheory) {
    const CantileverGeometry g;
    const StaticResult s2 = cantilever_static(g, 2), s4 = cantilever_static(g, 4), s6 = cantilever_static(g, 6);
    EXPECT_NEAR(s6.euler_bernoulli, 190.476e-6, 1e-9);
    EXPECT_LT(s2.deflection, s4.deflection);
    EXPECT_LT(s4.deflection, s6.deflection);
    EXPECT_LT(s6.deflection, s6.timoshenko);
    const double e4 = s4.timoshenko - s4.deflection, e6 = s6.timoshenko - s6.deflection;
    const double order = std::log(e4 / e6) / std::log(1.5);
    EXPECT_GT(order, 1.5);
    EXPECT_LT(order, 2.5);
    EXPECT_NEAR(s6.deflection / s6.euler_bernoulli, 0.9099, 5e-4);  // the measured value (docs/accuracy.md)
}

TEST(FemReference, CantileverFrequencyConvergesToBeamTheory) {
    const CantileverGeometry g;
    const FrequencyResult f4 = cantilever_frequency(g, 4), f6 = cantilever_frequency(g, 6);
    EXPECT_NEAR(f4.euler_bernoulli, 284.93, 0.01);
    EXPECT_GT(f4.modal, f6.modal);
    EXPECT_GT(f6.modal, f6.euler_bernoulli);
    EXPECT_NEAR(f6.modal / f6.euler_bernoulli, 1.0298, 5e-4);
}

// The implicit midpoint rule is the trapezoidal rule on a linear system: an oscillator of
// frequency w keeps its amplitude and its period lengthens to 2 atan(w h / 2) / h.
TEST(FemReference, MidpointPeriodAndEnergy) {
    const CantileverGeometry g;
    const int steps = 40;
    const FrequencyResult f = cantilever_frequency(g, 2, 10, steps);
    const double wh = 2 * M_PI * f.modal / (f.euler_bernoulli * steps);
    const double expected = std::atan(wh / 2) / (wh / 2);
    EXPECT_NEAR(f.dynamic / f.modal, expected, 2e-3);
    EXPECT_LT(f.energy_drift, 2e-6);
}

TEST(FemReference, BarWaveSpeed) {
    const FemMaterial glass;
    for (uint32_t cells : {1u, 2u}) {
        const WaveResult w = bar_wave_speed(glass, cells);
        EXPECT_NEAR(w.speed / w.theory, 1, 2e-3) << cells << " cells across";
    }
}

// A rigid rotation stores no energy in the corotational solid; in plain linear elasticity it
// stores the spurious strain of a linearized rotation.
TEST(FemReference, RigidRotationStoresNothing) {
    const TetMesh mesh = box_tet_mesh(Vec3(0.1, 0.02, 0.02), 10, 2, 2);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(1.2, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (bool co : {true, false}) {
        FemSettings s;
        s.corotational = co;
        s.gravity = Vec3::Zero();
        FemSolid solid(mesh, s);
        for (size_t v = 0; v < mesh.vertices.size(); ++v)
            solid.positions().segment<3>(3 * v) = R * mesh.vertices[v] + Vec3(0.3, -0.1, 0.2);
        Eigen::VectorXd f = Eigen::VectorXd::Zero(solid.positions().size());
        solid.elastic_forces(solid.positions(), f);
        if (co) {
            EXPECT_LT(solid.elastic_energy(), 1e-18);
            EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-6);  // N, against ~1e8 N for a 1 mm stretch
        } else {
            EXPECT_GT(solid.elastic_energy(), 1e3);
        }
    }
}

// Free tumbling at large rotation: the midpoint rule conserves energy only for a linear force.
// With corotation its error falls fast with the step, and it needs a step that resolves the
// rotation (docs/accuracy.md: at 200 steps per turn it blows up, as Simo & Tarnow showed for
// the midpoint rule in nonlinear elastodynamics).
TEST(FemReference, TumblingConservesEnergy) {
    const TumbleResult coarse = tumbling_bar(true, 200, 1, 400), fine = tumbling_bar(true, 200, 1, 800);
    std::printf("tumbling, 1 turn: energy drift %.3g at 400 steps per turn, %.3g at 800\n", coarse.energy_drift,
                fine.energy_drift);
    EXPECT_GT(coarse.energy_drift, 4 * fine.energy_drift);
    EXPECT_LT(fine.energy_drift, 1e-3);
}

// ---- interfaces (bench/fem_interfaces.h) ----

// While its ties hold, a scored solid is the whole solid (its copies share their vertex), and
// the ties carry the section's stress: the outer fibre reaches the strength near the load beam
// theory gives.
TEST(FemReference, ScoredCantileverIsWholeAndBreaksAtBeamTheory) {
    const CantileverGeometry g;
    const InterfaceStaticResult r = scored_cantilever(g, 4, 0.15);
    EXPECT_EQ(r.ties, 25u);  // 5 x 5 interface vertices
    EXPECT_NEAR(r.deflection_split / r.deflection_whole, 1, 1e-9);
    EXPECT_NEAR(r.beam_theory, 1200, 1e-9);
    EXPECT_NEAR(r.break_load / r.beam_theory, 1, 0.05);
    EXPECT_NEAR(r.break_load / r.beam_theory, 0.9698, 1e-3);  // the measured value (docs/accuracy.md)
}

// Pulled slowly, a bar's uniform stress reaches the strength at t = strength L / (E v), and every
// tie of the score lets go: two fragments.
TEST(FemReference, BarBreaksInTensionAtItsStrength) {
    const TensionBreakResult r = bar_tension_break(2);
    EXPECT_NEAR(r.break_time / r.predicted, 1, 0.01);
    EXPECT_EQ(r.broken, r.ties);
    EXPECT_EQ(r.fragments, 2u);
}

// ---- contact (bench/fem_contact.h) ----

// A block resting on the ground is held by contact forces that sum to its weight; slid at v0 it
// stops after v0^2 / (2 mu g) in v0 / (mu g), Coulomb's law.
TEST(FemReference, ContactHoldsTheWeightAndFrictionStopsASlide) {
    const TetMesh mesh = box_tet_mesh(Vec3(0.03, 0.03, 0.03), 2, 2, 2);
    FemSettings s;
    s.integrator = FemIntegrator::BackwardEuler;
    FemSolid solid(mesh, s);
    ContactSettings cs;
    cs.ground_friction = 0.3;
    attach_contact(solid, cs);
    const double h = 1e-3, v0 = 0.5, mu_g = 0.3 * 9.81;
    for (size_t v = 0; v < solid.vertex_count(); ++v) solid.velocities()[3 * v] = v0;
    double stop_time = -1, x_start = 0;
    for (size_t v = 0; v < solid.vertex_count(); ++v) x_start += solid.position(v).x() / double(solid.vertex_count());
    while (solid.time() < 0.4) {
        solid.step(h);
        double vx = 0;
        for (size_t v = 0; v < solid.vertex_count(); ++v) vx += solid.velocity(v).x() / double(solid.vertex_count());
        if (stop_time < 0 && vx < 0.01 * v0) stop_time = solid.time();
    }
    double x_end = 0, support = 0, mass = 0;
    for (size_t v = 0; v < solid.vertex_count(); ++v) {
        x_end += solid.position(v).x() / double(solid.vertex_count());
        support += cs.stiffness * std::max(0.0, -solid.position(v).y());
        mass += solid.lumped_mass()[3 * v];
    }
    EXPECT_NEAR(support / (mass * 9.81), 1, 1e-3);
    EXPECT_NEAR(stop_time, v0 / mu_g, 0.03 * v0 / mu_g);
    EXPECT_NEAR(x_end - x_start, v0 * v0 / (2 * mu_g), 0.03 * v0 * v0 / (2 * mu_g));
}

// A block thrown spinning against a wall stops there without gaining energy: every step's Newton iteration
// converges (the penalty contact's kinks are crossed by backtracking, and friction's normal force
// and contact set are the step's start's), and kinetic + elastic + gravitational energy never
// exceeds the start's. Before that, friction held the normal force of the step's first iterate
// and the iteration went round a cycle of two at contacts; the study's beam blew up after its
// first break (docs/log.md).
TEST(FemReference, BlockThrownAtAWallGainsNoEnergy) {
    const TetMesh mesh = box_tet_mesh(Vec3(0.03, 0.03, 0.03), 2, 2, 2);
    FemSettings s;
    s.integrator = FemIntegrator::BackwardEuler;
    FemSolid solid(mesh, s);
    ContactSettings cs;
    cs.ground_friction = 0.3;
    cs.boxes.push_back({Vec3(0.02, 0.05, 0.05), [](double) { return Vec3(0.06, 0.05, 0.015); }, 0.4});
    attach_contact(solid, cs);
    // Tilted about two axes and 1 cm up, so that an edge meets the ground and a corner the wall,
    // thrown at 2 m/s along x, spinning at 20 rad/s.
    const Vec3 c(0.015, 0.015, 0.015);
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.3, Vec3(0, 1, 0)) * Eigen::AngleAxisd(0.2, Vec3(1, 0, 0))).toRotationMatrix();
    for (size_t v = 0; v < solid.vertex_count(); ++v) {
        const Vec3 p = R * (mesh.vertices[v] - c) + c + Vec3(0, 0.01, 0);
        solid.positions().segment<3>(3 * v) = p;
        solid.velocities().segment<3>(3 * v) = Vec3(2, 0, 0) + Vec3(0, 20, 5).cross(p - c);
    }
    const auto energy = [&] { return solid.kinetic_energy() + solid.elastic_energy() + solid.gravity_energy(); };
    const double e0 = energy();
    double worst = 0, reach = -1;
    const double h = 2e-4;
    while (solid.time() < 0.1) {
        solid.step(h);
        worst = std::max(worst, energy() - e0);
        for (size_t v = 0; v < solid.vertex_count(); ++v) reach = std::max(reach, solid.position(v).x());
    }
    std::printf("block at a wall: energy gain at most %.3g J of %.3g J; halved steps %ld, unconverged %ld; reached "
                "x = %.5f m (the wall at 0.04)\n", worst, e0, solid.halved_steps(), solid.unconverged_steps(), reach);
    EXPECT_GT(reach, 0.04);  // it hit the wall
    EXPECT_LT(worst, 1e-6 * e0);
    EXPECT_EQ(solid.unconverged_steps(), 0);
}

// Regular 1:8 refinement: every child has an eighth of its parent's volume (the 4 corner tets are
// the parent halved; the octahedron's 4 have the same volume whichever diagonal cuts it), keeps
// the parent's piece, and keeps the interface whole: the same area, tied by the old vertices and
// the new edge midpoints.
TEST(FemReference, RefinedTetsKeepVolumePiecesAndInterfaces) {
    TetMesh mesh = box_tet_mesh(Vec3(0.02, 0.01, 0.01), 2, 1, 1);
    std::vector<uint32_t> piece(mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) piece[t] = t < 6 ? 0 : 1;  // the x < 0.01 cell is piece 0
    const TetMesh before = mesh;
    const std::vector<uint32_t> piece_before = piece;
    refine_tets(mesh, piece);
    ASSERT_EQ(mesh.tets.size(), 8 * before.tets.size());
    const auto volume = [](const TetMesh& m, const Tet& t) {
        return tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
    };
    for (size_t t = 0; t < before.tets.size(); ++t)
        for (size_t c = 0; c < 8; ++c) {
            EXPECT_NEAR(volume(mesh, mesh.tets[8 * t + c]), volume(before, before.tets[t]) / 8, 1e-21);
            EXPECT_EQ(piece[8 * t + c], piece_before[t]);
        }
    // The 1 x 1 cm shared face: 2 x 2 vertices, 3 x 3 after one refinement.
    const SplitMesh coarse = split_pieces(before, piece_before), fine = split_pieces(mesh, piece);
    EXPECT_EQ(coarse.ties.size(), 4u);
    EXPECT_EQ(fine.ties.size(), 9u);
    double area = 0;
    for (const Tie& t : fine.ties) area += t.area;
    EXPECT_NEAR(area, 1e-4, 1e-15);
}

// A model of boxes (the plate's kind) meshed as Kuhn tets: cells lie in one box each, the boxes'
// volumes add up, and the shared face is tied by (cells + 1)^2 ties over its area; the stiffness
// length is the shortest box side.
TEST(FemReference, BoxModelTets) {
    Model model;
    const auto box = [](Vec3 lo, Vec3 size) {
        Piece p;
        for (int c = 0; c < 8; ++c)
            p.surface.vertices.push_back(lo + Vec3(c & 1 ? size.x() : 0, c & 2 ? size.y() : 0, c & 4 ? size.z() : 0));
        return p;
    };
    model.pieces = {box(Vec3(0, 0, 0), Vec3(0.03, 0.03, 0.03)), box(Vec3(0.03, 0, 0), Vec3(0.06, 0.03, 0.03))};
    EXPECT_DOUBLE_EQ(stiffness_length(model), 0.03);
    TetMesh mesh;
    std::vector<uint32_t> piece;
    box_model_tets(model, 2, mesh, piece);
    ASSERT_EQ(mesh.tets.size(), size_t(6 * (8 + 16)));
    double v[2] = {0, 0};
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& q = mesh.tets[t];
        v[piece[t]] += tet_volume(mesh.vertices[q[0]], mesh.vertices[q[1]], mesh.vertices[q[2]], mesh.vertices[q[3]]);
    }
    EXPECT_NEAR(v[0], 2.7e-5, 1e-15);
    EXPECT_NEAR(v[1], 5.4e-5, 1e-15);
    const SplitMesh split = split_pieces(mesh, piece);
    EXPECT_EQ(split.ties.size(), 9u);
    double area = 0;
    for (const Tie& t : split.ties) area += t.area;
    EXPECT_NEAR(area, 9e-4, 1e-15);
}
