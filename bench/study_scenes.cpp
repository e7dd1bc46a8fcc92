// The study's scenes with their fixed settings (copied from assets/*.toml at the commit the study
// was written against; docs/accuracy.md lists them), the rigs, and the breaking methods.
#include <chrono>
#include <cmath>

#include "bench/study.h"
#include "core/error.h"
#include "prescore/prescore.h"
#include "scenes/paper_scenes.h"

namespace shatter::study {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

StudyCase generated(const std::string& scene, const GenerateSettings& g) {
    StudyCase c;
    c.scene = scene;
    const auto t0 = std::chrono::steady_clock::now();
    c.model = generate_model(g);
    c.prescore_seconds = seconds_since(t0);
    return c;
}

ColliderSettings box_collider(const char* name, Vec3 size, Vec3 position) {
    ColliderSettings s;
    s.name = name;
    s.shape.size = size;
    s.pose.position = position;
    return s;
}

ColliderSettings sphere_collider(double radius) {
    ColliderSettings s;
    s.name = "sphere";
    s.shape.kind = ShapeKind::Sphere;
    s.shape.radius = radius;
    s.pose.position = Vec3(0, radius, 0);
    return s;
}

// The study's scenes solve their joints one row at a time, the solve whose steps, iterations and
// failures it measures (iterative joints, by name), but for the chain;
// the rows that say "+direct" or "+auto" solve them directly or as shipped.
void common_simulate(SimulateSettings& s, double duration, uint32_t iterations) {
    s.duration = duration;
    s.fps = 30;
    s.substeps = 8;
    s.iterations = iterations;
    s.joints = JointSolve::Iterative;
    s.exact_energy = true;
}

}  // namespace

// assets/beam.toml: a glass beam of two 30 cm halves pushed through two posts; breaks at ~0.30 s.
StudyCase beam_case(const ModelKnobs& k) {
    GenerateSettings g = default_generate(GenerateKind::Beam);
    g.count = 2;
    g.size = Vec3(0.3, 0.03, 0.03);
    g.constraints_per_side = k.constraints_per_side ? k.constraints_per_side : 2;
    g.density = 2500;
    StudyCase c = generated("beam", g);
    SimulationInput& in = c.input;
    in.scene.ground_surface.friction = 0.3;
    in.scene.colliders = {box_collider("left post", Vec3(0.04, 0.3, 0.04), Vec3(-0.2, 0.15, -0.0355)),
                          box_collider("right post", Vec3(0.04, 0.3, 0.04), Vec3(0.2, 0.15, -0.0355))};
    KinematicSettings block;
    block.name = "block";
    block.shape.size = Vec3(0.08, 0.06, 0.06);
    block.keys = {{0, Vec3(0, 0.032, 0.1)}, {0.2, Vec3(0, 0.032, 0.046)}, {1.5, Vec3(0, 0.032, 0.02)}};
    in.scene.kinematic = {block};
    in.material.stiffness = 5.25e11;
    in.material.strength = 2.31e7;
    in.material.alpha = 1;
    in.material.surface = {0.4, 0.1};
    common_simulate(in.simulate, 0.6, 3000);
    return c;
}

// assets/plate.toml: 5 x 5 plaster cubes of 3 cm dropped from 0.48 m onto a 6 cm sphere.
StudyCase plate_case(const ModelKnobs& k) {
    GenerateSettings g = default_generate(GenerateKind::Plate);
    g.count = 5;
    g.size = Vec3(0.03, 0.03, 0.03);
    g.constraints_per_side = k.constraints_per_side ? k.constraints_per_side : 2;
    g.density = 1200;
    StudyCase c = generated("plate", g);
    SimulationInput& in = c.input;
    in.scene.colliders = {sphere_collider(0.06)};
    in.object.pose.position = Vec3(0, 0.6, 0);
    in.material.stiffness = 5e10;
    in.material.strength = 1e5;
    in.material.alpha = 1;
    in.material.surface = {0.5, 0.1};
    common_simulate(in.simulate, 0.6, 20);
    return c;
}

// assets/chain.toml: 10 porcelain links between two end cubes that move apart after 0.3 s.
StudyCase chain_case(const ModelKnobs& k) {
    GenerateSettings g = default_generate(GenerateKind::Chain);
    g.count = 10;
    g.size = Vec3(0.03, 0.01, 0.01);
    g.end_size = 0.05;
    g.constraints_per_side = k.constraints_per_side ? k.constraints_per_side : 1;
    g.density = 2400;
    StudyCase c = generated("chain", g);
    SimulationInput& in = c.input;
    PieceDriveSettings left, right;
    left.piece = 0;
    left.keys = {{0, Vec3::Zero()}, {0.3, Vec3::Zero()}, {3, Vec3(-0.03, 0, 0)}};
    right.piece = g.count + 1;
    right.keys = {{0, Vec3::Zero()}, {0.3, Vec3::Zero()}, {3, Vec3(0.03, 0, 0)}};
    in.object.driven = {left, right};
    in.material.stiffness = 1e8;
    in.material.strength = 1e5;
    in.material.alpha = 1;
    in.material.surface = {0.5, 0.1};
    common_simulate(in.simulate, 1.5, 20);
    in.simulate.joints = JointSolve::Direct;  // as assets/chain.toml: its end cubes are 42 times a link
    in.simulate.rate_limit = 0.3;
    c.reference_substeps_factor = 2;  // CFM: the chain's soft joints refuse h / 4 and below (docs/accuracy.md)
    return c;
}

// assets/bunny_sphere.toml: the hollow glmark2 bunny (10 pieces, 20 cm) dropped from 1.5 m onto an
// 8 cm sphere; breaks on impact at ~0.51 s.
StudyCase bunny_case(const ModelKnobs& k) {
    StudyCase c;
    c.scene = "bunny";
    MeshSettings mesh;
    mesh.path = "/usr/share/glmark2/models/bunny.obj";
    mesh.scale = 0.1;
    PrescoreSettings ps;
    ps.pieces = 10;
    ps.seed = 1;
    ps.hollow = Length{0.06, true};
    ps.resolution = k.resolution;
    ps.density = 1100;
    ps.collision_max_parts = k.collision_max_parts;
    ps.constraints_per_pair = k.constraints_per_pair;
    const auto t0 = std::chrono::steady_clock::now();
    c.model = prescore(mesh, ps, nullptr);
    c.prescore_seconds = seconds_since(t0);
    SimulationInput& in = c.input;
    in.scene.colliders = {sphere_collider(0.08)};
    in.object.pose.position = Vec3(0, 1.5, 0);
    in.material.stiffness = 3e9;
    in.material.strength = 2e4;
    in.material.alpha = 1;
    in.material.surface = {0.6, 0.1};
    common_simulate(in.simulate, 0.8, 20);
    return c;
}

StudyCase make_case(const std::string& scene, const ModelKnobs& k) {
    if (scene == "beam") return beam_case(k);
    if (scene == "plate") return plate_case(k);
    if (scene == "chain") return chain_case(k);
    if (scene == "bunny") return bunny_case(k);
    throw Error(ExitCode::Usage, "study: unknown scene '" + scene + "' (beam, plate, chain, bunny)");
}

StudyCase rig_case(const RigSettings& r) {
    GenerateSettings g = default_generate(GenerateKind::Beam);
    g.count = 3;
    g.size = Vec3(0.1, 0.02, 0.02);
    g.constraints_per_side = 2;
    g.density = 2500;
    StudyCase c = generated("rig", g);
    Piece& p2 = c.model.pieces[2];
    p2.mass.mass *= r.mass_ratio;
    p2.mass.inertia *= r.mass_ratio;
    SimulationInput& in = c.input;
    in.scene.ground = false;
    PieceDriveSettings anchor;
    anchor.piece = 0;
    anchor.fixed = true;
    in.object.driven = {anchor};
    // The static force on one root constraint: the bending moment of pieces 1 and 2 about the root
    // face over 4 constraints at +-a (a = half-height / sqrt(3)), and the shear over 4.
    const double m1 = c.model.pieces[1].mass.mass, m2 = p2.mass.mass, L = g.size.x(), gy = 9.81;
    const double moment = gy * (m1 * 0.5 * L + m2 * 1.5 * L), a = 0.5 * g.size.y() / std::sqrt(3.0);
    const double f_root = std::hypot(moment / (4 * a), gy * (m1 + m2) / 4);
    const double area = c.model.constraints.front().area;
    in.material.stiffness = r.stiffness;
    in.material.strength = r.strength_fraction * f_root / area;
    in.material.alpha = r.alpha;
    in.material.damping = 0;
    in.simulate.duration = r.duration;
    in.simulate.fps = r.fps;
    in.simulate.substeps = r.substeps;
    in.simulate.iterations = 20;
    in.simulate.joints = JointSolve::Iterative;  // as common_simulate
    in.simulate.exact_energy = true;
    return c;
}

StudyCase stiffness_rig_case(double stiffness, uint32_t substeps, uint32_t iterations) {
    GenerateSettings g = default_generate(GenerateKind::Beam);
    g.count = 2;
    g.size = Vec3(0.1, 0.02, 0.02);
    g.constraints_per_side = 2;
    g.density = 2500;
    StudyCase c = generated("stiffness_rig", g);
    SimulationInput& in = c.input;
    in.scene.ground = false;
    in.scene.gravity = Vec3(9.81, 0, 0);
    PieceDriveSettings anchor;
    anchor.piece = 0;
    anchor.fixed = true;
    in.object.driven = {anchor};
    in.material.stiffness = stiffness;
    // Undamped: the backward-Euler step damps the spring's oscillation (its period is shorter than
    // the step) and the bar settles within the run; a damper would slow the solver's convergence.
    in.material.damping = 0;
    in.material.strength = 1e12;
    in.material.alpha = 0;
    in.simulate.duration = 0.25;
    in.simulate.fps = 120;
    in.simulate.substeps = substeps;
    in.simulate.iterations = iterations;
    in.simulate.joints = JointSolve::Iterative;  // as common_simulate
    return c;
}

const std::vector<Method>& methods() {
    static const std::vector<Method> m = {
        {"plain", "plain deletion (alpha = 0)"},
        {"bullet", "Bullet's per-row impulse threshold (alpha = 0)"},
        {"paper", "energized, the paper read literally (alpha E per body, paper magnitudes)"},
        {"energized", "energized, our split (alpha E in all, exact energy), the paper's directions"},
        {"opposed", "energized, momentum-conserving (opposed kicks): the default method"},
        {"rate_limit", "energized + rate limit 0.05 s"},
        {"rollback", "energized + rollback"},
    };
    return m;
}

void apply_method(const std::string& method, SimulationInput& in) {
    SimulateSettings& s = in.simulate;
    s.rate_limit = 0;
    s.rollback = false;
    s.energy_split = EnergySplitMode::Total;
    s.directions = KickDirectionMode::Paper;
    s.exact_energy = true;
    s.break_criterion = BreakCriterion::Force;
    if (method == "plain") {
        in.material.alpha = 0;
    } else if (method == "bullet") {
        in.material.alpha = 0;
        s.break_criterion = BreakCriterion::BulletImpulse;
    } else if (method == "paper") {
        s.energy_split = EnergySplitMode::PerBody;
        s.exact_energy = false;
    } else if (method == "energized") {
    } else if (method == "opposed") {
        s.directions = KickDirectionMode::Opposed;
    } else if (method == "rate_limit") {
        s.rate_limit = 0.05;
    } else if (method == "rollback") {
        s.rollback = true;
    } else {
        throw Error(ExitCode::Usage, "study: unknown method '" + method + "'");
    }
}

}  // namespace shatter::study
