// The stability map's 3D scenes (docs/accuracy.md section 6.1): boxes generated as a beam
// (scenes/paper_scenes.h) stood upright, or a plate, joined by point constraints; each run is
// classified like the map (refused / NaN / energy growth / cascade / fly-apart) and then held to
// what "stable" means physically for that scene:
//
//   hanging      a heavy block hanging on a light chain of ball joints from a fixed link; the
//                block is mass_ratio x a link; strength 4 x the static load on the top joint.
//                Stable: no break, the block's sag (mean over the last 0.2 s) within 5% of
//                sum_j W_j / k_j (W_j the weight below joint j, k_j its stiffness), the kinetic
//                energy over the last 0.2 s under 10% of its peak.
//   alternating  the same with 10 links, joint stiffness alternating 1e3 : 1e6 N/m, damped.
//   stack        a tower of boxes standing on the ground, masses growing geometrically from the
//                bottom box to the top one (mass_ratio), joined by breakable constraints
//                (strength 3 x the static load on the bottom joint). Stable: no break, the top
//                box moved < 1 mm after 1 s and is at rest (< 1 cm/s) at the end. Two variants
//                tell the ground contact's part from the joints': "stack_fixed" the bottom box
//                fixed and no ground, "stack_it200" 200 solver iterations (Bullet's contacts are
//                always solved iteratively).
//   tower        a welded tower of 8 equal cubes standing free on the ground, hit at box 5 by a
//                kinematic sphere (10 m/s, 1 cm into the tower, then back): the tower is knocked
//                over as one body. Stable: no joint broken that does not hold the hit box, no
//                unbroken joint ever open by more than 1 mm (nothing flies apart), and no box two
//                or more away from the hit faster than 2 x the sphere (a rigid tower struck at
//                10 m/s with restitution 0.1 turns about its base: its top reaches ~1.1 x 10 x
//                0.30 / 0.22 = 15 m/s). Joint strength 10 MPa; "tower_weak" the same at 1 MPa,
//                where the hit breaks joints.
//   grid         a 30 x 30 plate of cubes hanging from its two top corners (grid_case).
//   wall         a 10 x 10 wall of welded 5 cm concrete cubes on a fixed bottom row, hit by three
//                steel balls (projectiles, 0.88 kg at 10 m/s) at three places 0.1 s apart.
//                Stable: every broken joint lies next to a hit (its pivot within
//                kWallDamageRadius of the point a ball was aimed at) and no unbroken joint is ever
//                open by more than 1 mm. Joint strength 2 MPa; "wall_weak" the same at 1 MPa.
//
// Header-only so that tests/simulate/stability_scenes_test.cpp pins the same scenes.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench/study.h"
#include "core/error.h"
#include "scenes/paper_scenes.h"

namespace shatter::study::scenes3d {

inline const std::vector<std::string>& names() {
    static const std::vector<std::string> n = {"hanging", "alternating", "stack",      "stack_fixed",
                                               "stack_it200", "tower",     "tower_weak", "wall",
                                               "wall_weak",   "grid"};
    return n;
}

// The tower's hit: box kHitBox (from the bottom) of kTowerBoxes, from t = kHitStart.
inline constexpr uint32_t kTowerBoxes = 8, kHitBox = 5;
inline constexpr double kHitStart = 0.1, kHitSpeed = 10, kSphereRadius = 0.03, kTowerEdge = 0.04;

inline StudyCase upright(const std::string& name, uint32_t count, Vec3 size, uint32_t per_side, double density) {
    GenerateSettings g = default_generate(GenerateKind::Beam);
    g.count = count;
    g.size = size;
    g.constraints_per_side = per_side;
    g.density = density;
    StudyCase c;
    c.scene = name;
    c.model = generate_model(g);
    SimulationInput& in = c.input;
    in.object.pose.rotation_deg = Vec3(0, 0, 90);  // the row's x along y: piece 0 at the bottom
    in.object.place = Placement::Base;
    in.material.damping = 0;
    in.material.alpha = 1;
    in.simulate.fps = 120;
    in.simulate.substeps = 8;
    in.simulate.iterations = 20;
    in.simulate.exact_energy = true;
    return c;
}

inline void scale_mass(Piece& p, double f) {
    p.mass.mass *= f;
    p.mass.inertia *= f;
}

// Joint j: the constraints between pieces j and j + 1; its stiffness stiffness x their area.
inline double joint_area(const Model& m, uint32_t j) {
    double a = 0;
    for (const Constraint& k : m.constraints)
        if (k.piece_a == j && k.piece_b == j + 1) a += k.area;
    return a;
}

// Piece 0 the block, 1..links the chain's links (3 x 1 x 1 cm porcelain, ball joints at the
// face centres), piece links + 1 fixed at the top. No ground. `alternate`: joints 0, 2, 4, ...
// (from the block up) stand for 1/1,000 of their face (k = 1e3 N/m against the others' 1e6 N/m).
inline StudyCase hanging_case(double mass_ratio, uint32_t links = 6, bool alternate = false) {
    StudyCase c = upright(alternate ? "alternating" : "hanging", links + 2, Vec3(0.03, 0.01, 0.01), 1, 2400);
    scale_mass(c.model.pieces[0], mass_ratio);
    if (alternate)
        for (Constraint& k : c.model.constraints)
            if (k.piece_a % 2 == 0) k.area *= 1e-3;
    SimulationInput& in = c.input;
    in.scene.ground = false;
    in.object.pose.position = Vec3(0, 0.5, 0);
    PieceDriveSettings anchor;
    anchor.piece = links + 1;
    anchor.fixed = true;
    in.object.driven = {anchor};
    double w = 0;  // the load on the top joint
    for (uint32_t p = 0; p <= links; ++p) w += c.model.pieces[p].mass.mass * 9.81;
    in.material.stiffness = 1e10;  // 1e6 N/m per joint
    in.material.strength = 4 * w / joint_area(c.model, links);  // twice the drop's peak load
    in.simulate.duration = 1;
    if (alternate) {
        // Stiffness-proportional damping (damping / stiffness = 0.03 s): the chain's slowest mode,
        // the block on six soft springs in series (~60 rad/s at ratio 1), critically damped.
        in.material.strength = 4 * w / std::min(joint_area(c.model, links), joint_area(c.model, 0));
        in.material.damping = 0.03 * in.material.stiffness;
    }
    return c;
}

// A 30 x 30 plate of 1 cm plaster cubes (2 x 2 constraints per face: a stiff plate, 6,960
// constraints) standing in the xy plane, hanging from its two top corners, no ground; never
// breaks under its weight (strength 10 x the corner's static load). Stable: no break, no
// fly-apart, kinetic energy over the last 0.2 s under 10% of its peak. (Direct joints: ~30 s a run.)
// A plate of n x n cubes of `edge` (2 x 2 constraints per face) turned 90 degrees about x to stand
// in the xy plane (world y = -model z, world z = model y), no ground.
inline StudyCase plate_standing(const std::string& name, uint32_t n, double edge, double density) {
    GenerateSettings g = default_generate(GenerateKind::Plate);
    g.count = n;
    g.size = Vec3(edge, edge, edge);
    g.constraints_per_side = 2;
    g.density = density;
    StudyCase c;
    c.scene = name;
    c.model = generate_model(g);
    c.input.object.pose.rotation_deg = Vec3(90, 0, 0);
    c.input.scene.ground = false;
    return c;
}

inline StudyCase grid_case(uint32_t n = 30, double duration = 0.5) {
    const double edge = 0.01;
    StudyCase c = plate_standing("grid", n, edge, 1200);
    SimulationInput& in = c.input;
    in.object.pose.position = Vec3(0, 1, 0);
    // The two corner cubes with the largest y after the rotation: in the model frame, the row
    // z = min (x = min and x = max); the plate's piece order is not assumed.
    uint32_t a = 0, b = 0;
    double best_a = INFINITY, best_b = INFINITY;
    for (uint32_t p = 0; p < c.model.pieces.size(); ++p) {
        const Vec3 x = c.model.pieces[p].mass.center;
        if (x.z() - x.x() < best_a) best_a = x.z() - x.x(), a = p;
        if (x.z() + x.x() < best_b) best_b = x.z() + x.x(), b = p;
    }
    PieceDriveSettings ca, cb;
    ca.piece = a;
    ca.fixed = true;
    cb.piece = b;
    cb.fixed = true;
    in.object.driven = {ca, cb};
    double mass = 0;
    for (const Piece& p : c.model.pieces) mass += p.mass.mass;
    in.material.stiffness = 1e10;
    in.material.damping = 0;
    in.material.strength = 10 * 0.5 * mass * 9.81 / (edge * edge);
    in.material.alpha = 1;
    in.simulate.duration = duration;
    in.simulate.fps = 120;
    in.simulate.substeps = 8;
    in.simulate.iterations = 20;
    return c;
}

// 4 cubes of 5 cm, the bottom one 1,000 kg/m^3 (125 g), each next one mass_ratio^(1/3) heavier.
inline StudyCase stack_case(double mass_ratio, uint32_t boxes = 4) {
    StudyCase c = upright("stack", boxes, Vec3(0.05, 0.05, 0.05), 2, 1000);
    double above = 0;  // the weight on the bottom joint
    for (uint32_t i = 0; i < boxes; ++i) {
        scale_mass(c.model.pieces[i], std::pow(mass_ratio, double(i) / (boxes - 1)));
        if (i > 0) above += c.model.pieces[i].mass.mass * 9.81;
    }
    SimulationInput& in = c.input;
    in.material.stiffness = 1e10;  // 2.5e7 N/m per joint
    in.material.strength = 3 * above / joint_area(c.model, 0);
    in.simulate.duration = 1;
    return c;
}

// 8 glass cubes of 4 cm welded by 2 x 2 constraints (strength 10 MPa: 16 kN per face), the sphere
// along +z at box 5's height, 1 cm into the tower at kHitStart + 11 ms, back out 11 ms later.
inline StudyCase tower_case(double strength = 1e7, double speed = kHitSpeed) {
    StudyCase c = upright("tower", kTowerBoxes, Vec3(kTowerEdge, kTowerEdge, kTowerEdge), 2, 2500);
    SimulationInput& in = c.input;
    in.material.stiffness = 1e10;
    in.material.strength = strength;
    KinematicSettings s;
    s.name = "sphere";
    s.shape.kind = ShapeKind::Sphere;
    s.shape.radius = kSphereRadius;
    const double y = (kHitBox + 0.5) * kTowerEdge, z_in = -0.5 * kTowerEdge - kSphereRadius + 0.01, z0 = z_in - 0.11;
    const double t_in = 0.11 / speed;
    s.pose.position = Vec3(0, y, z0);
    s.keys = {{0, Vec3(0, y, z0)}, {kHitStart, Vec3(0, y, z0)}, {kHitStart + t_in, Vec3(0, y, z_in)},
              {kHitStart + 2 * t_in, Vec3(0, y, z0)}};
    in.scene.kinematic = {s};
    in.simulate.duration = 0.5;
    return c;
}

// The wall: kWallCubes x kWallCubes concrete cubes of kWallEdge in the xy plane (z through its
// thickness), 2 x 2 constraints per face, the bottom row fixed, no ground. Ball i (kSphereRadius,
// steel) is aimed at the centre of a cube's front face (kWallHits: column, row from the bottom
// left) to arrive at kHitStart + 0.1 i s, thrown at t = 0 from kHitSpeed x that time in front of
// it (gravity's drop aimed for). A joint is "next to a hit" when its pivot lies within
// kWallDamageRadius of a struck point: the hit cube's own joints (2.5 to 3.5 cm away) and those
// of the ring of cubes around it (up to 7.9 cm) are; the next ring's (from 8.4 cm) are not.
inline constexpr uint32_t kWallCubes = 10;
inline constexpr double kWallEdge = 0.05, kWallDamageRadius = 0.08;
inline constexpr uint32_t kWallHits[3][2] = {{2, 7}, {7, 7}, {5, 3}};

// Where ball i strikes (the centre of its cube's front face, world frame).
inline Vec3 wall_hit_point(uint32_t i) {
    return Vec3((kWallHits[i][0] + 0.5 - 0.5 * kWallCubes) * kWallEdge, (kWallHits[i][1] + 0.5) * kWallEdge,
                -0.5 * kWallEdge);
}

inline StudyCase wall_case(double strength = 2e6) {
    // Placed on its base: the wall stands on y = 0 centred on x = 0 and z = 0, its front face at
    // z = -kWallEdge / 2; its bottom row (the largest model z) is fixed.
    StudyCase c = plate_standing("wall", kWallCubes, kWallEdge, 2400);
    SimulationInput& in = c.input;
    in.object.place = Placement::Base;
    double bottom = -INFINITY;
    for (const Piece& p : c.model.pieces) bottom = std::max(bottom, p.mass.center.z());
    for (uint32_t p = 0; p < c.model.pieces.size(); ++p)
        if (c.model.pieces[p].mass.center.z() > bottom - 0.5 * kWallEdge) {
            PieceDriveSettings fixed;
            fixed.piece = p;
            fixed.fixed = true;
            in.object.driven.push_back(fixed);
        }
    in.material.stiffness = 1e10;
    in.material.damping = 0;
    in.material.strength = strength;
    in.material.alpha = 1;
    const Vec3 gravity = in.scene.gravity;
    for (uint32_t i = 0; i < 3; ++i) {
        ProjectileSettings b;
        b.name = "ball " + std::to_string(i + 1);
        b.shape.kind = ShapeKind::Sphere;
        b.shape.radius = kSphereRadius;
        b.density = 7800;
        b.surface = {0.5, 0.1};
        // Arrives touching the face at time T: p(T) = p0 + v T + g T^2 / 2.
        const double T = kHitStart + 0.1 * i;
        const Vec3 arrive = wall_hit_point(i) - Vec3(0, 0, kSphereRadius);
        const Vec3 start = arrive - Vec3(0, 0, kHitSpeed * T);
        b.pose.position = start;
        b.velocity = (arrive - start - 0.5 * gravity * T * T) / T;
        in.scene.projectiles.push_back(b);
    }
    in.simulate.duration = 0.6;
    in.simulate.fps = 120;
    in.simulate.substeps = 8;
    in.simulate.iterations = 20;
    in.simulate.exact_energy = true;
    return c;
}

inline StudyCase make_scene(const std::string& name, double mass_ratio) {
    if (name == "hanging") return hanging_case(mass_ratio);
    if (name == "stack") return stack_case(mass_ratio);
    if (name == "stack_fixed" || name == "stack_it200") {
        StudyCase c = stack_case(mass_ratio);
        c.scene = name;
        if (name == "stack_it200") {
            c.input.simulate.iterations = 200;
        } else {
            c.input.scene.ground = false;
            PieceDriveSettings bottom;
            bottom.piece = 0;
            bottom.fixed = true;
            c.input.object.driven = {bottom};
        }
        return c;
    }
    if (name == "alternating") return hanging_case(mass_ratio, 10, true);
    if (name == "grid") return grid_case();
    if (name == "wall") return wall_case();
    if (name == "wall_weak") {
        StudyCase c = wall_case(1e6);
        c.scene = "wall_weak";
        return c;
    }
    if (name == "tower") return tower_case();
    if (name == "tower_weak") {
        StudyCase c = tower_case(1e6);
        c.scene = "tower_weak";
        return c;
    }
    throw Error(ExitCode::Usage, "study: unknown 3D stability scene '" + name + "'");
}

// ---- the verdict ---------------------------------------------------------------------------

struct Verdict {
    Stability cls = Stability::Stable;  // the map's class (the tower: no energy test, the sphere does work)
    bool physical = false;              // the scene's own "stable" (above)
    bool stable() const { return cls == Stability::Stable && physical; }
    size_t breaks = 0;
    size_t far_breaks = 0;  // tower: joints not touching the hit box
    // hanging, alternating: sag / expected - 1; stack: top displacement (m); tower: far boxes' top
    // speed (m/s); grid: the largest displacement of a cube at the end (m)
    double measure = NAN;
    double ke_end = NAN;    // kinetic energy, mean over the last 0.2 s (J)
    double ke_peak = NAN;
    double top_speed = NAN; // stack: the top box's speed at the end (m/s)
    double open = NAN;      // tower: the widest an unbroken joint opened (m)
    bool guard_refuses = false;  // the CFM guard (max_cfm 0.5) refused; the run is then without it
};

inline Vec3 centre(const Trajectory& t, uint32_t f, uint32_t piece) { return t.pose(f, piece).position.cast<double>(); }

// The hanging chains: joint j's static stretch, the weight below it over its stiffness (unit: m);
// 0 in the other scenes.
inline double static_stretch(const StudyCase& c, uint32_t j) {
    if (c.scene != "hanging" && c.scene != "alternating") return 0;
    double below = 0;
    for (uint32_t p = 0; p <= j; ++p) below += c.model.pieces[p].mass.mass * c.input.scene.gravity.norm();
    return below / (c.input.material.stiffness * joint_area(c.model, j));
}

// As classify (bench/study_metrics.cpp): a run that stopped (NaN, or the instability guard's
// energy limit), energy growth beyond what the breaks injected plus 10% of max(injected, m g
// 10 cm), more than half the constraints broken within 0.1 s, a pivot gap > 1 mm before the first
// break (in a hanging chain: 1 mm + twice the joint's static stretch).
inline Stability map_class(const StudyCase& c, const SimulationResult& r, bool refused, bool energy_test) {
    if (refused) return Stability::Refused;
    if (!r.complete) return r.stop_reason.find("NaN") != std::string::npos ? Stability::NaN : Stability::EnergyGrowth;
    if (energy_test && energy_growth_test(c, r).grew) return Stability::EnergyGrowth;
    if (2 * most_breaks_within(r.breaks, 0.1) > c.model.constraints.size()) return Stability::Cascade;
    const Trajectory& t = r.trajectory;
    const double t_break = r.breaks.empty() ? INFINITY : r.breaks.front().time;
    for (uint32_t f = 0; f < t.frames() && f / t.fps < t_break - 1e-12; ++f)
        for (const Constraint& k : c.model.constraints) {
            // A hanging chain's joint may stretch twice its static stretch (released at rest).
            const double allow = 1e-3 + 2 * static_stretch(c, k.piece_a);
            auto at = [&](uint32_t piece) {
                const BodyPose& pose = t.pose(f, piece);
                return Vec3(pose.rotation.cast<double>() * (k.pivot - c.model.pieces[piece].mass.center) +
                            pose.position.cast<double>());
            };
            if ((at(k.piece_a) - at(k.piece_b)).norm() > allow) return Stability::FlyApart;
        }
    return Stability::Stable;
}

// The widest any constraint's two pivots (each carried by its piece) were apart in a recorded
// frame before it broke (unit: m).
inline double widest_open(const StudyCase& c, const SimulationResult& r) {
    const Trajectory& t = r.trajectory;
    std::vector<double> until(c.model.constraints.size(), INFINITY);
    for (const BreakRecord& b : r.breaks) until[b.constraint] = std::min(until[b.constraint], b.time);
    double open = 0;
    for (uint32_t f = 0; f < t.frames(); ++f)
        for (size_t i = 0; i < c.model.constraints.size(); ++i) {
            if (f / t.fps >= until[i] - 1e-12) continue;
            const Constraint& k = c.model.constraints[i];
            auto at = [&](uint32_t piece) {
                const BodyPose& pose = t.pose(f, piece);
                return Vec3(pose.rotation.cast<double>() * (k.pivot - c.model.pieces[piece].mass.center) +
                            pose.position.cast<double>());
            };
            open = std::max(open, (at(k.piece_a) - at(k.piece_b)).norm());
        }
    return open;
}

inline Verdict judge(const StudyCase& c, const SimulationResult& r, bool refused) {
    Verdict v;
    const bool tower = c.scene.rfind("tower", 0) == 0;
    v.cls = map_class(c, r, refused, !tower);
    if (refused) return v;
    v.breaks = r.breaks.size();
    const Trajectory& t = r.trajectory;
    const uint32_t frames = t.frames();
    const double duration = c.input.simulate.duration;
    v.ke_peak = 0;
    double ke_sum = 0;
    size_t ke_n = 0;
    for (const EnergySample& e : r.energy) {
        v.ke_peak = std::max(v.ke_peak, e.kinetic);
        if (e.time >= duration - 0.2 - 1e-9) ke_sum += e.kinetic, ke_n++;
    }
    v.ke_end = ke_n ? ke_sum / ke_n : NAN;
    if (!r.complete || frames < 2) return v;
    const double g = c.input.scene.gravity.norm();
    if (c.scene == "hanging" || c.scene == "alternating") {
        // Expected sag: sum over joints j (pieces j, j + 1) of the weight below over k_j.
        const uint32_t n = uint32_t(c.model.pieces.size());
        double below = 0, sag = 0;
        for (uint32_t j = 0; j + 1 < n; ++j) {
            below += c.model.pieces[j].mass.mass * g;
            sag += below / (c.input.material.stiffness * joint_area(c.model, j));
        }
        double y = 0;
        uint32_t m = 0;
        for (uint32_t f = 0; f < frames; ++f)
            if (f / t.fps >= duration - 0.2 - 1e-9) y += centre(t, f, 0).y(), m++;
        const double measured = centre(t, 0, 0).y() - y / m;
        v.measure = measured / sag - 1;
        v.physical = v.breaks == 0 && std::abs(v.measure) < 0.05 && v.ke_end < 0.1 * v.ke_peak;
    } else if (c.scene.rfind("stack", 0) == 0) {
        const uint32_t top = uint32_t(c.model.pieces.size()) - 1;
        v.measure = (centre(t, frames - 1, top) - centre(t, 0, top)).norm();
        v.top_speed = (centre(t, frames - 1, top) - centre(t, frames - 2, top)).norm() * t.fps;
        v.physical = v.breaks == 0 && v.measure < 1e-3 && v.top_speed < 0.01;
    } else if (c.scene.rfind("wall", 0) == 0) {
        // Each broken joint's pivot where the wall stood, against the struck points.
        const Mat3 rot = rotation_matrix(c.input.object.pose.rotation_deg);
        const Vec3 move = object_translation(c.model, c.input.object);
        v.measure = 0;
        for (const BreakRecord& b : r.breaks) {
            const Vec3 pivot = rot * c.model.constraints[b.constraint].pivot + move;
            double nearest = INFINITY;
            for (uint32_t i = 0; i < 3; ++i) nearest = std::min(nearest, (pivot - wall_hit_point(i)).norm());
            v.measure = std::max(v.measure, nearest);
            v.far_breaks += nearest > kWallDamageRadius;
        }
        v.open = widest_open(c, r);
        v.physical = v.far_breaks == 0 && v.open < 1e-3;
    } else if (c.scene == "grid") {
        v.measure = 0;
        for (uint32_t p = 0; p < c.model.pieces.size(); ++p)
            v.measure = std::max(v.measure, (centre(t, frames - 1, p) - centre(t, 0, p)).norm());
        v.physical = v.breaks == 0 && v.ke_end < 0.1 * v.ke_peak;
    } else {
        for (const BreakRecord& b : r.breaks) v.far_breaks += b.piece_a != kHitBox && b.piece_b != kHitBox;
        v.measure = 0;
        for (uint32_t f = 1; f < frames; ++f)
            for (uint32_t p = 0; p < kTowerBoxes; ++p)
                if (p + 2 <= kHitBox || p >= kHitBox + 2)
                    v.measure = std::max(v.measure, (centre(t, f, p) - centre(t, f - 1, p)).norm() * t.fps);
        v.open = widest_open(c, r);
        v.physical = v.far_breaks == 0 && v.open < 1e-3 && v.measure < 2 * kHitSpeed;
    }
    return v;
}

inline SimulationResult run_once(const StudyCase& c, bool* refused) {
    *refused = false;
    try {
        return simulate(c.model, c.input, "study");
    } catch (const Error& e) {
        if (e.code() != ExitCode::BadInput) throw;
        *refused = true;
        SimulationResult r;
        r.complete = false;
        return r;
    }
}

// As the map's cells: with the CFM guard (max_cfm 0.5); when it refuses, again without it
// (max_cfm 0.99) to see what the guard prevents.
inline Verdict run_and_judge(StudyCase c) {
    c.input.simulate.max_cfm = 0.5;
    bool refused = false;
    SimulationResult r = run_once(c, &refused);
    if (!refused) return judge(c, r, false);
    c.input.simulate.max_cfm = 0.99;
    r = run_once(c, &refused);
    Verdict v = judge(c, r, refused);
    v.guard_refuses = true;
    return v;
}

}  // namespace shatter::study::scenes3d
