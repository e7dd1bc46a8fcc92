#include "simulate/simulate.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "core/log.h"
#include "core/material_presets.h"
#include "core/progress.h"
#include "core/stage_file.h"
#include "simulate/auto_step.h"
#include "simulate/bullet_world.h"
#include "simulate/instability.h"
#include "simulate/rest_check.h"
#include "simulate/spring.h"
#include "simulate/stepper.h"

namespace shatter {

namespace {

// The least [material] stiffness number (stiffness in N/m^3, or youngs_modulus in Pa when it is
// set: core/material_presets.h) with which every constraint's CFM stays within max_cfm at this
// step (0 when the shot's already does), and the first constraint that needs more.
double least_stiffness(const BulletWorld& world, const Model& model, const SimulationInput& in, size_t* first) {
    double need = 0;
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        if (!world.active(c)) continue;
        double w = 0;
        const double cfm = world.current_max_cfm(c, &w);
        if (cfm <= in.simulate.max_cfm) continue;
        const Constraint& constraint = model.constraints[c];
        const double k_min = min_stiffness_for_cfm(in.material.damping * constraint.area, world.h(), w,
                                                   in.simulate.max_cfm) /
                             stiffness_factor(in.material, model, constraint);
        if (need == 0) *first = c;
        need = std::max(need, k_min);
    }
    return need;
}

// Refuses constraints whose spring is too soft for its bodies at this step: the solver diverges
// as CFM nears 1 (simulate/spring.h).
void check_cfm(const BulletWorld& world, const Model& model, const SimulationInput& in) {
    size_t c = 0;
    const double k_min = least_stiffness(world, model, in, &c);
    if (k_min == 0) return;
    double w = 0;
    const char* key = stiffness_number_key(in.material);
    const char* unit = stiffness_number_unit(in.material);
    throw_input_error(
        fmt::format("[material] {}", key),
        fmt::format("constraint {} (pieces {} and {}) would need CFM {:.3g} at the step h = {:.4g} s with {} "
                    "{:.4g} {}{}; the solver converges only below CFM {:g} (max_cfm)",
                    c, world.piece_a(c), world.piece_b(c), world.current_max_cfm(c, &w), world.h(), key,
                    stiffness_number(in.material), unit,
                    in.material.preset != "none" ? fmt::format(" (preset \"{}\")", in.material.preset) : "",
                    in.simulate.max_cfm),
        fmt::format("raise [material] {} to at least {:.3g} {} (or damping), set [material] stiffen = true, "
                    "or use fewer [simulate] substeps: a longer step lowers CFM",
                    key, k_min, unit));
}

// What the run chose by itself ({"what", "why"} each, logged) and what it warned of before it
// started: both kept in the trajectory's settings.
struct Choices {
    nlohmann::ordered_json chosen = nlohmann::ordered_json::array();
    std::vector<std::string> warned;
    void choose(const std::string& what, const std::string& why) {
        spdlog::info("auto: {} ({})", what, why);
        chosen.push_back({{"what", what}, {"why", why}});
    }
};

// joints = "auto": the solve it took. Iterative joints by name are warned where the mass ratios
// pass those at which they start to fail.
void explain_joints(const Model& model, const SimulationInput& in, bool direct, Choices& choices) {
    if (model.constraints.empty()) return;
    if (in.simulate.joints == JointSolve::Auto) {
        choices.choose("[simulate] joints = \"direct\"",
                       fmt::format("{} pieces: every model's joints solved directly", model.pieces.size()));
        return;
    }
    if (direct) return;
    uint32_t heavy = 0, light = 0, island_heavy = 0, island_light = 0;
    const double ratio = largest_joined_mass_ratio(model, &heavy, &light);
    const double island = largest_island_mass_ratio(model, &island_heavy, &island_light);
    if (ratio <= kIterativeMassRatio && island <= kIterativeIslandRatio) return;
    const bool joined = ratio > kIterativeMassRatio;
    warn_and_keep(choices.warned,
                  fmt::format("simulate: joints = \"iterative\", but piece {} is {:.3g} times as heavy as piece {} {}: "
                              "iterative joints may break or drift apart where they should hold from a mass ratio of "
                              "{:g} (docs/accuracy.md, \"The stability map\"). [simulate] joints = \"direct\" (the "
                              "default) holds them",
                              joined ? heavy : island_heavy, joined ? ratio : island, joined ? light : island_light,
                              joined ? "joined to it" : "in its island of joined pieces",
                              joined ? kIterativeMassRatio : kIterativeIslandRatio));
}

// [material] stiffen: a stiffness too soft for the step (pieces smaller or heavier than the shot
// was tuned for) is raised to the least that converges, with a margin, instead of refused; the
// trajectory's settings then hold the stiffness used.
void stiffen(const Model& model, SimulationInput& in, double h, Choices& choices) {
    const bool bullet_impulse = in.simulate.break_criterion == BreakCriterion::BulletImpulse;
    size_t first = 0;
    const double need = least_stiffness(BulletWorld(model, {in.scene, in.object, in.material, h,
                                                             in.simulate.iterations, bullet_impulse}),
                                        model, in, &first);
    if (need > 0) {
        const double stiffness = 1.05 * need;
        choices.choose(fmt::format("{} {:.4g} -> {:.4g} {}", stiffness_number_key(in.material), stiffness_number(in.material),
                                   stiffness, stiffness_number_unit(in.material)),
                       fmt::format("constraint {} would need CFM above {:g} at h = {:.4g} s; [material] stiffen = true", first,
                                   in.simulate.max_cfm, h));
        set_stiffness_number(in.material, stiffness);
    }
}

// `chosen`: what simulate chose by itself ({"what", "why"} each), kept under "auto" when any;
// `warnings`: what it warned of, under "warnings" when any.
std::string trajectory_settings(const SimulationInput& in, const std::string& model_id, const Model& model,
                                const nlohmann::ordered_json& chosen, const std::vector<std::string>& warnings) {
    nlohmann::ordered_json j;
    j["model"] = {{"fnv1a64", model_id}, {"pieces", model.pieces.size()}};
    j["scene"] = to_json(in.scene);
    j["object"] = to_json(in.object);
    j["material"] = to_json(in.material);
    j["simulate"] = to_json(in.simulate);
    if (!chosen.empty()) j["auto"] = chosen;
    if (!warnings.empty()) j["warnings"] = warnings;
    return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);  // (a collider mesh's path)
}

void record(const BulletWorld& world, Trajectory& t) {
    for (uint32_t p = 0; p < world.pieces(); ++p) t.poses.push_back(world.piece_pose(p));
    for (uint32_t p = 0; p < world.props(); ++p) t.poses.push_back(world.prop_pose(p));
}

// After a step: false when the run must stop (a NaN, or runaway energy with on_instability = stop);
// runaway energy with clamp scales the velocities down to the limit and is counted.
bool check_stability(BulletWorld& world, const InstabilityGuard& guard, double injected, InstabilityMode mode,
                     SimulationResult& out) {
    if (InstabilityGuard::non_finite(world)) {
        out.complete = false;
        out.stop_reason = InstabilityGuard::describe_non_finite(world, out.breaks, &out.stopped_at);
        return false;
    }
    const EnergyLimit e = guard.limit(world, injected);
    if (!(e.kinetic > e.limit)) return true;
    if (mode == InstabilityMode::Stop) {
        out.complete = false;
        out.stop_reason = InstabilityGuard::describe_runaway(e, world, out.breaks, &out.stopped_at);
        return false;
    }
    if (out.clamps++ == 0) {
        out.first_clamp = InstabilityGuard::describe_runaway(e, world, out.breaks, &out.first_clamp_at);
        warn_and_keep(out.warnings, "simulate: clamping velocities (on_instability = clamp): " + out.first_clamp);
    }
    world.scale_piece_velocities(std::sqrt(e.limit / e.kinetic));
    return true;
}

// duration = "auto" and the pieces never came to rest: the piece that moves most for its size,
// and, when the joints that hold it all lie on one line (one joint: a ball; more: a hinge) to one
// neighbour, that: such a piece swings about them, with nothing but the joints' damping to stop it
// while it does not turn into its neighbour (kOverlapBreak; docs/physics.md section 3).
void warn_still_moving(const BulletWorld& world, const std::vector<double>& radius, const SimulateSettings& s,
                       std::vector<std::string>& kept) {
    uint32_t worst = 0;
    if (most_moving(world, radius, &worst) < 0) return;
    std::vector<Vec3> pivots;
    std::vector<uint32_t> neighbours;
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        if (!world.active(c) || (world.piece_a(c) != worst && world.piece_b(c) != worst)) continue;
        Vec3 p;
        world.bodies_at_pivot(c, &p);
        pivots.push_back(p);
        neighbours.push_back(world.piece_a(c) == worst ? world.piece_b(c) : world.piece_a(c));
    }
    std::string held;
    if (!pivots.empty() && std::all_of(neighbours.begin(), neighbours.end(), [&](uint32_t n) { return n == neighbours[0]; })) {
        // On one line: every pivot within a twentieth of the piece's radius of the line through the
        // first pivot and the one farthest from it.
        size_t far = 0;
        for (size_t i = 1; i < pivots.size(); ++i)
            if ((pivots[i] - pivots[0]).norm() > (pivots[far] - pivots[0]).norm()) far = i;
        const Vec3 d = (pivots[far] - pivots[0]).normalized();
        bool line = true;
        for (size_t i = 1; i < pivots.size() && far > 0; ++i) {
            const Vec3 r = pivots[i] - pivots[0];
            if ((r - r.dot(d) * d).norm() > 0.05 * radius[worst]) line = false;
        }
        if (line)
            held = fmt::format(", held to piece {} by {} on one line (a {}), about which it swings (docs/physics.md "
                               "section 3)",
                               neighbours[0], pivots.size() == 1 ? "one joint" : fmt::format("{} joints", pivots.size()),
                               pivots.size() == 1 ? "ball joint" : "hinge");
    }
    warn_and_keep(kept, fmt::format("simulate: the pieces were still moving at max_duration = {:g} s (duration = "
                                    "\"auto\"): piece {} at {:.3g} m/s and {:.3g} rad/s{}. The movie runs to "
                                    "max_duration; a fixed [simulate] duration ends it sooner",
                                    s.max_duration, worst, world.piece_velocity(worst).norm(),
                                    world.piece_angular_velocity(worst).norm(), held));
}

// The run of one shot: the world, the stepper, the guard and the records, and the stages of a frame
// that simulate() calls in order.
class Simulation {
public:
    Simulation(const Model& model, const SimulationInput& in, const WorldSetup& setup, double block, uint32_t blocks,
               SimulationResult& out)
        : model_(model), in_(in), out_(out), world_(model, setup), radius_(piece_radii(model, world_)),
          run_(in, world_, radius_), guard_(world_, model, in.scene, in.object, in.material),
          rest_(model, world_, radius_, in.simulate.fps),
          auto_step_(run_, world_, radius_, block, setup.direct_joints, in.simulate.max_cfm), blocks_(blocks),
          rest_speed_(rest_speed(model, in.scene.gravity.norm())),
          hold_frames_(uint32_t(std::ceil(kRestHold * in.simulate.fps - 1e-9))) {}

    BulletWorld& world() { return world_; }
    const std::vector<double>& radius() const { return radius_; }
    // Whether the object hit something: its first contact with the scene came after its first
    // step (an object that starts resting on the ground, the chain, hit nothing by that).
    bool hit() const { return hit_; }

    // Stage "step" of frame f: its fixed substeps, or the automatic step's blocks; each step
    // followed by the stepper's stages and the guard (after_step).
    void step_frame(uint32_t f) {
        frame_ = f;
        if (in_.simulate.auto_substeps) {
            auto_step_.frame(blocks_, out_, [this] { return after_step(); }, landed_);
            return;
        }
        for (uint32_t s = 0; s < in_.simulate.substeps; ++s) {
            run_.substep(out_);
            if (!after_step()) break;
        }
    }

    // Stage "record": the frame's poses and energy books.
    void record_frame() {
        record(world_, out_.trajectory);
        out_.energy.push_back(run_.books());
    }

    // duration = "auto": every piece has rested for the hold up to frame f (and the rest time is
    // kept). The hold begins no earlier than the frame the object landed in: the fall before it
    // does not count.
    bool at_rest(uint32_t f) {
        if (!in_.simulate.auto_duration || f < hold_from_ + hold_frames_ ||
            !rest_.stayed(out_.trajectory, f - hold_frames_, f, rest_speed_, landed_))
            return false;
        out_.rest_time = (f - hold_frames_) / in_.simulate.fps;
        return true;
    }

private:
    static std::vector<double> piece_radii(const Model& model, const BulletWorld& world) {
        std::vector<double> radius(world.pieces(), 0.0);
        for (uint32_t i = 0; i < world.pieces() && i < model.pieces.size(); ++i) radius[i] = piece_radius(model.pieces[i]);
        return radius;
    }

    // Stage "guard", after every kept step: the driven pieces' work, whether the object has landed,
    // and the instability check (false: the run stops).
    // Until the object first touches the scene (or breaks), the rest speed is capped by the fall
    // (rest_speed); from then on it is the object's own (rest_speed_landed): a 600 m object
    // whose last piece slides at 6 m/s moves under half a pixel a frame in a movie that frames it.
    // (substeps = "auto" spans blocks only from then on too.)
    bool after_step() {
        guard_.after_step(world_);
        if (!touched_ && world_.touches_scene()) touched_ = true, hit_ = out_.steps > 1;
        if (!landed_ && (in_.simulate.auto_duration || in_.simulate.auto_substeps) &&
            (!out_.breaks.empty() || touched_)) {
            landed_ = true;
            rest_speed_ = rest_speed_landed(model_);
            hold_from_ = frame_;
        }
        return check_stability(world_, guard_, run_.injected(), in_.simulate.on_instability, out_);
    }

    const Model& model_;
    const SimulationInput& in_;
    SimulationResult& out_;
    BulletWorld world_;
    const std::vector<double> radius_;  // each piece's (piece_radius; 0 for a prop)
    Stepper run_;
    InstabilityGuard guard_;
    RestCheck rest_;
    AutoStep auto_step_;
    const uint32_t blocks_;  // substeps = "auto": blocks per frame
    double rest_speed_;      // (unit: m/s)
    const uint32_t hold_frames_;
    bool touched_ = false, hit_ = false, landed_ = false;
    uint32_t hold_from_ = 0, frame_ = 0;
};

// The warnings of a finished run: pieces still moving at max_duration, a piece deep inside what
// it hit, a stiff material that broke nothing at a fixed step, joints whose forces did not match
// their stretch before the first break; and how long the object flew as one body.
void warn_at_end(Simulation& sim, const SimulationInput& in, double h, double stiffest, bool direct,
                 SimulationResult& out) {
    const BulletWorld& world = sim.world();
    if (in.simulate.auto_duration && out.complete && out.rest_time < 0) warn_still_moving(world, sim.radius(), in.simulate, out.warnings);
    if (out.deepest.depth_per_radius > kDeepContactWarning) {
        // A step 2^k times shorter, k enough to bring the depth under half the radius were it in
        // proportion to the step (it falls less: docs/log.md, "Why a small piece sinks").
        double factor = 1;
        while (factor < 4096 && out.deepest.depth_per_radius / factor > 0.5) factor *= 2;
        const double h_then = out.deepest_step / factor;
        const auto substeps = uint32_t(std::ceil(1.0 / (in.simulate.fps * h_then) - 1e-9));
        warn_and_keep(out.warnings,
             fmt::format("simulate: piece {} was {:.3g} mm inside what it touches at {:.4f} s, {:.2g} times its "
                         "radius ({:.3g} mm), after a step of h = {:.3g} s: at this step small pieces move further "
                         "than their size at the impact's speed, and one can end inside the ground or another piece, "
                         "where the contacts no longer push it out. A finer step, [simulate] substeps = {} (h = "
                         "{:.3g} s), lets them in less deep",
                         out.deepest.piece, 1e3 * out.deepest.depth, out.deepest_time, out.deepest.depth_per_radius,
                         1e3 * out.deepest.depth / out.deepest.depth_per_radius, out.deepest_step, substeps,
                         1.0 / (in.simulate.fps * substeps)));
    }
    if (world.flying())
        spdlog::info("simulate: the object moved as one rigid body for the whole run: nothing came within contact "
                     "reach ([simulate] rigid_flight)");
    else if (world.flight_end() > 0)
        spdlog::info("simulate: the object fell as one rigid body until {:.4f} s, when something came within contact "
                     "reach ([simulate] rigid_flight)",
                     world.flight_end());
    if (out.breaks.empty() && sim.hit() && !in.simulate.auto_substeps && stiffest * h > kStiffStepWarning)
        warn_and_keep(out.warnings,
             fmt::format("simulate: no joint broke, and at this step (h = {:.3g} s) the stiffest joint has omega h = "
                         "{:.0f}: an impact's peak force is resolved to about 1/{:.0f} of itself (docs/physics.md "
                         "section 7). [simulate] substeps = \"auto\" (the default, which this shot's fixed step replaces) "
                         "resolves it",
                         h, stiffest * h, stiffest * h));
    // Before the first break, a structure under load should hold forces its stretch explains;
    // an impact's pushes (docs/physics.md section 5a) are not the solve's to fix.
    const ResidualPeak& r = out.residual_before_break;
    if (r.residual > kResidualTolerance)
        warn_and_keep(out.warnings,
             fmt::format("simulate: the joints' forces do not match their stretch: up to {:.1f}% of the strength off "
                         "(constraint {}, pieces {} and {}, at {:.4f} s, before the first break; tolerance {:g}%): the "
                         "solve, or a contact's push, left them apart, so a break's energy (read from its force) is "
                         "not what its stretch held (docs/physics.md sections 5a and 5b; {})",
                         100 * r.residual, r.constraint, world.piece_a(size_t(r.constraint)),
                         world.piece_b(size_t(r.constraint)), r.time, 100 * kResidualTolerance,
                         direct ? fmt::format("more [simulate] iterations let the direct solve converge further, now {}",
                                              in.simulate.iterations)
                                : fmt::format("[simulate] joints = \"direct\" solves the joints exactly and moves "
                                              "joined pieces together when contacts push them; or more [simulate] "
                                              "iterations, now {}",
                                              in.simulate.iterations)));
    // Iterative joints that broke holding more by their stretch than their forces stored: the
    // books count the stored energy, and the rest left with the pieces unaccounted.
    double stored = 0;
    for (const BreakRecord& b : out.breaks) stored += b.kicks.stored_energy;
    const double stretch = out.energy.empty() ? 0.0 : out.energy.back().removed;
    if (!direct && stored > 0 && stretch > (1 + kIterativeStretchExcess) * stored)
        warn_and_keep(out.warnings,
             fmt::format("simulate: the {} joints that broke held {:.4g} J by their stretch, {:.3g} times the {:.4g} J "
                         "their forces stored and the books count: iterative joints (joints = \"iterative\") left "
                         "their forces short of their springs, and each break gave back alpha times its force's "
                         "energy, not its spring's. [simulate] joints = \"direct\" (the default) keeps every joint's "
                         "force to its stretch (docs/physics.md section 5b)",
                         out.breaks.size(), stretch, stretch / stored, stored));
}

}  // namespace

double largest_joined_mass_ratio(const Model& model, uint32_t* heavier, uint32_t* lighter) {
    double largest = 0;
    for (const Constraint& c : model.constraints) {
        const double ma = model.pieces[c.piece_a].mass.mass, mb = model.pieces[c.piece_b].mass.mass;
        const double lo = std::min(ma, mb), hi = std::max(ma, mb);
        if (!(lo > 0) || !(hi > largest * lo)) continue;
        largest = hi / lo;
        if (heavier) *heavier = ma >= mb ? c.piece_a : c.piece_b;
        if (lighter) *lighter = ma >= mb ? c.piece_b : c.piece_a;
    }
    return std::max(largest, 1.0);
}

double largest_island_mass_ratio(const Model& model, uint32_t* heavier, uint32_t* lighter) {
    const std::vector<uint32_t> island = fragment_of(model);
    // Per island (by the piece that names it): its heaviest and lightest piece with mass.
    std::vector<uint32_t> most(island.size(), UINT32_MAX), least(island.size(), UINT32_MAX);
    const auto mass = [&model](uint32_t p) { return model.pieces[p].mass.mass; };
    for (uint32_t p = 0; p < island.size(); ++p) {
        if (!(mass(p) > 0)) continue;
        const uint32_t root = island[p];
        if (most[root] == UINT32_MAX || mass(p) > mass(most[root])) most[root] = p;
        if (least[root] == UINT32_MAX || mass(p) < mass(least[root])) least[root] = p;
    }
    double largest = 1;
    for (uint32_t root = 0; root < island.size(); ++root) {
        if (most[root] == UINT32_MAX || !(mass(most[root]) > largest * mass(least[root]))) continue;
        largest = mass(most[root]) / mass(least[root]);
        if (heavier) *heavier = most[root];
        if (lighter) *lighter = least[root];
    }
    return largest;
}

bool solves_joints_directly(const Model&, const SimulateSettings& s) { return s.joints != JointSolve::Iterative; }

uint32_t frame_count(const SimulateSettings& s) {
    return uint32_t(std::llround((s.auto_duration ? s.max_duration : s.duration) * s.fps)) + 1;
}

SimulationResult simulate(const Model& model, const SimulationInput& shot_input, const std::string& model_id) {
    // A run is a fixed list of stages:
    //   choose     the joint solve (joints = "auto") and, for iterative joints, the stiffness
    //              (stiffen) or the refusal of one too soft for the step (check_cfm)
    //   frame 0    the poses and books before the first step
    //   per frame  step (Simulation::step_frame: each step's save, step, measure, pick breaks,
    //              roll back or remove, energize in Stepper, then the guard), record, and the
    //              rest check of duration = "auto"
    //   end        the run's warnings, then the settings, which keep them
    // With substeps = "auto" the world starts at the coarsest step, a whole block (the CFM check
    // and stiffen then hold for every step the run takes: auto_split keeps the fine ones within
    // max_cfm).
    const uint32_t blocks = uint32_t(std::max(1.0, std::ceil(1.0 / (shot_input.simulate.fps * kAutoBlock) - 1e-9)));
    const double block = 1.0 / (shot_input.simulate.fps * blocks);
    const double h = shot_input.simulate.auto_substeps ? block : 1.0 / (shot_input.simulate.fps * shot_input.simulate.substeps);
    SimulationInput in = shot_input;
    // Direct joints solve every joint row exactly whatever its CFM: no stiffness is too soft for
    // the step (docs/physics.md section 5b), so neither stiffen nor the CFM check applies.
    const bool direct = solves_joints_directly(model, in.simulate);
    Choices choices;
    explain_joints(model, in, direct, choices);
    if (in.material.stiffen && !direct) stiffen(model, in, h, choices);
    WorldSetup setup{in.scene, in.object, in.material, h, in.simulate.iterations,
                     in.simulate.break_criterion == BreakCriterion::BulletImpulse};
    setup.direct_joints = direct;
    setup.rigid_flight = in.simulate.rigid_flight;
    if (in.simulate.sleep) setup.sleep_speed = kSleepSpeed;
    setup.threads = in.threads;

    SimulationResult out;
    Simulation sim(model, in, setup, block, blocks, out);
    BulletWorld& world = sim.world();
    if (!direct) check_cfm(world, model, in);
    double stiffest = 0, softest = 0;  // (unit: rad/s)
    world.joint_frequencies(&stiffest, &softest);
    out.warnings = std::move(choices.warned);
    Trajectory& t = out.trajectory;
    t.producer = producer_string();
    t.fps = in.simulate.fps;
    t.pieces = world.pieces();
    t.props = world.props();
    sim.record_frame();

    const uint32_t frames = frame_count(in.simulate);
    Progress progress("simulate", frames - 1);
    for (uint32_t f = 1; f < frames && out.complete; ++f) {
        sim.step_frame(f);
        if (!out.complete) break;
        sim.record_frame();
        progress.advance();
        if (sim.at_rest(f)) break;
    }
    t.complete = out.complete;
    out.asleep = world.sleeping_pieces();
    out.parallel_contact_tests = world.parallel_contact_tests();
    warn_at_end(sim, in, h, stiffest, direct, out);
    // The settings last: they keep every warning of the run.
    t.settings_json = trajectory_settings(in, model_id, model, choices.chosen, out.warnings);
    return out;
}

}  // namespace shatter
