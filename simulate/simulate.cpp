#include "simulate/simulate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "core/log.h"
#include "core/material_presets.h"
#include "core/progress.h"
#include "core/stage_file.h"
#include "simulate/break_policy.h"
#include "simulate/breaking.h"
#include "simulate/bullet_world.h"
#include "simulate/instability.h"
#include "simulate/spring.h"

namespace shatter {

namespace {

EnergizeSettings energize_settings(const SimulationInput& in) {
    EnergizeSettings e;
    e.alpha = in.material.alpha;
    e.split = in.simulate.energy_split == EnergySplitMode::PerBody ? EnergySplit::PerBody : EnergySplit::Total;
    switch (in.simulate.directions) {
        case KickDirectionMode::Paper: e.directions = KickDirections::Paper; break;
        case KickDirectionMode::Opposed: e.directions = KickDirections::Opposed; break;
        case KickDirectionMode::Force: e.directions = KickDirections::Force; break;
    }
    e.exact_energy = in.simulate.exact_energy;
    e.bodies = in.simulate.kick_bodies == KickBodiesMode::Joined ? KickBodies::Joined : KickBodies::Pieces;
    return e;
}

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

class Run {
public:
    // `radius`: each piece's (piece_radius; 0 for a prop).
    Run(const SimulationInput& in, BulletWorld& world, const std::vector<double>& radius)
        : in_(in), world_(world), radius_(radius), policy_(in.simulate.rate_limit), energize_(energize_settings(in)) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> id;
        pair_of_.resize(world_.constraint_count());
        for (size_t c = 0; c < pair_of_.size(); ++c) {
            const uint32_t a = world_.piece_a(c), b = world_.piece_b(c);
            const auto [at, added] = id.emplace(std::make_pair(std::min(a, b), std::max(a, b)), uint32_t(pair_joints_.size()));
            if (added) pair_joints_.emplace_back();
            pair_joints_[at->second].push_back(c);
            pair_of_[c] = at->second;
        }
    }

    void substep(SimulationResult& out) {
        std::shared_ptr<BulletWorld::Snapshot> start;
        if (in_.simulate.rollback) start = world_.save();
        world_.step();
        after_step(out, start);
    }

    // The automatic step's probe: one step of the whole block, kept and processed as any step when
    // every joint carries less than kAutoRefineLoad of its strength; otherwise undone (false).
    // The joints' forces the probe is compared with are their mean forces over the block before it
    // (its impulse over its time): after fine steps, a joint that rings at its own frequency (which
    // a coarse step does not resolve and damps) has the mean of its ringing, not the force of the
    // last fine step.
    // `h` is the probe's length: the block's, or a part of it (the block then in steps of h).
    bool probe(SimulationResult& out, double h) {
        const std::shared_ptr<BulletWorld::Snapshot> start = world_.save();
        before_.resize(world_.constraint_count());
        for (size_t c = 0; c < before_.size(); ++c)
            before_[c] = !world_.active(c) ? Vec3::Zero()
                         : block_time_ > 0 ? Vec3(block_impulse_[c] / block_time_)
                                           : world_.force_on_a(c);
        world_.set_step(h);
        world_.step();
        const double load = impact_load(*start);
        const double approach = world_.approach_load();
        other_load_ = std::max(other_load_, approach);
        if (!(load < kAutoRefineLoad) || !(approach < kAutoRefineLoad)) {
            world_.restore(*start);
            world_.forget_contact_impulses();
            for (size_t c = 0; c < world_.constraint_count(); ++c)
                if (world_.bullet_disabled(c)) world_.enable(c);  // Bullet's own break, undone too
            ++out.rejected_steps;
            return false;
        }
        after_step(out, in_.simulate.rollback ? start : nullptr);
        return true;
    }

    // After a step: the residual, then the step's breaks (a rollback from `start` re-runs it).
    void after_step(SimulationResult& out, const std::shared_ptr<BulletWorld::Snapshot>& start) {
        ++out.steps;
        out.solver_iterations += uint64_t(world_.last_step_iterations());
        int64_t worst = -1;
        const double r = world_.max_joint_residual(&worst);
        frame_residual_ = std::max(frame_residual_, r);
        if (r > out.residual.residual) out.residual = {r, world_.time(), worst};
        const DeepContact deep = world_.last_step_deepest_contact();
        if (deep.depth_per_radius > out.deepest.depth_per_radius)
            out.deepest = deep, out.deepest_time = world_.time(), out.deepest_step = world_.h();
        std::vector<Overload> over = find_overloads(world_, in_.simulate.break_criterion);
        add_overlapped(over);
        const std::vector<size_t> broken = policy_.select(over, world_.time());
        if (broken.empty() && out.breaks.empty() && r > out.residual_before_break.residual)
            out.residual_before_break = {r, world_.time(), worst};
        if (broken.empty()) return;
        // The load at the break defines E and the directions; a rollback re-runs the step without
        // the broken constraints, and the impulses then act on the re-run state.
        std::vector<std::array<BodyAtPivot, 2>> loads;
        for (size_t c : broken) {
            Vec3 pivot;
            loads.push_back(world_.bodies_at_pivot(c, &pivot));
        }
        if (start) world_.restore(*start);
        for (size_t c : broken) world_.remove_constraint(c);
        if (start) world_.step();
        // Each break's energy is counted in its pair's frame in the state the kicks act on (the
        // re-run one after a rollback), before any of this step's kicks: docs/physics.md section 4.
        // With joined kicks, in the frame of everything joined to the two pieces (the world's when
        // that holds a static or kinematic piece: an anchor takes the momentum the kicks give it).
        // (Energizing's time, for the benchmark, from here: finding what each kick moves is its work.)
        const auto start_energize = std::chrono::steady_clock::now();
        std::vector<Vec3> frames;
        std::vector<std::optional<BulletWorld::JoinedPieces>> joined(broken.size());
        split_held_.clear();
        if (energize_.bodies == KickBodies::Joined) {
            world_.fragments(&fragments_);
            for (size_t h = 0; h < held_.size(); ++h)
                if (split(held_[h])) split_held_.push_back(h);
        }
        for (size_t i = 0; i < broken.size(); ++i) {
            if (energize_.bodies == KickBodies::Joined) {
                joined[i].emplace();
                world_.joined_pieces(broken[i], kJoinedPiecesLimit, fragments_, &*joined[i]);
                frames.push_back(world_.frame_velocity(joined[i]->pieces));
            } else {
                Vec3 pivot;
                const std::array<BodyAtPivot, 2> now = world_.bodies_at_pivot(broken[i], &pivot);
                frames.push_back(pair_frame_velocity(now[0], now[1]));
            }
        }
        out.energize_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_energize).count();
        for (size_t i = 0; i < broken.size(); ++i) {
            energize_break(broken[i], loads[i], frames[i], joined[i] ? &*joined[i] : nullptr, out);
            if (broken[i] < overlap_.size()) out.breaks.back().overlap = overlap_[broken[i]];
        }
        held_.erase(std::remove_if(held_.begin(), held_.end(), [](const Held& h) { return h.released; }), held_.end());
        // The pairs this step's breaks touched, for the overlap check (ascending), which drops those
        // no joint holds any more.
        for (size_t c : broken) {
            const uint32_t p = pair_of_[c];
            const auto at = std::lower_bound(partly_joined_.begin(), partly_joined_.end(), p);
            if (at == partly_joined_.end() || *at != p) partly_joined_.insert(at, p);
        }
    }

    double injected() const { return injected_; }  // (unit: J)

    // After a refused probe: by how many times (a power of two) a shorter step may pass the probe's
    // test, or 1 when none may. Only a probe refused for its joints' stretch alone (the solver's
    // forces, their sudden changes and approaching contacts all under kAutoRefineLoad) is split: a
    // step on joined pieces that turn parts their pivots by about (omega h)^2 |r| / 2 (docs/physics.md
    // section 7a), which falls as the square of the step.
    uint32_t finer_split() const {
        if (!(other_load_ < kAutoRefineLoad) || !std::isfinite(spring_load_)) return 1;
        uint32_t m = 2;
        while (m < kAutoMaxSplit && !(spring_load_ / (double(m) * m) < kAutoRefineLoad)) m *= 2;
        return m;
    }
    double spring_load() const { return spring_load_; }  // the last probe's, over strength
    double other_load() const { return other_load_; }    // the same, by everything else

    // The automatic step's record of a block: each joint's impulse over the block's steps so far,
    // and whether the block is in fine steps.
    void start_block(bool fine) {
        block_impulse_.assign(world_.constraint_count(), Vec3::Zero());
        block_time_ = 0;
        block_fine_ = fine;
    }
    void add_to_block() {
        const double h = world_.h();
        for (size_t c = 0; c < block_impulse_.size(); ++c)
            if (world_.active(c)) block_impulse_[c] += h * world_.force_on_a(c);
        block_time_ += h;
    }

    // The largest load of the probe step over the joints' strength, counting a sudden one at the
    // force the joint would really reach: a change df of a joint's force within a step that treats
    // it as rigid (omega h > 1) stands for a relative velocity jump whose peak force is
    // omega h |df| (docs/physics.md section 7), where the step itself shows only df; no more than
    // the peak force of the jump its bodies' velocities show from `start` to now (a load moved
    // between joints that balance on their bodies, as a slow pull loads a chain, is no impact).
    // Also keeps its two parts (spring_load_, other_load_), of which it is the larger.
    double impact_load(const BulletWorld::Snapshot& start) {
        spring_load_ = other_load_ = 0;
        const auto over = [](double x, double s) { return s > 0 ? x / s : (x > 0 ? INFINITY : 0.0); };
        for (size_t c = 0; c < world_.constraint_count(); ++c) {
            if (!world_.active(c) || !world_.awake(c)) continue;  // asleep: unchanged since its last solve
            const Vec3 f = world_.force_on_a(c);
            const double omega_h = world_.joint_frequency(c) * world_.h();
            // The spring's own force k |d| too: a solve that did not converge shows less than
            // the stretch holds (docs/physics.md section 5a).
            const double spring = world_.stiffness(c) * world_.joint_stretch(c).stretch.norm();
            const double s = world_.strength(c);
            // A solve that stops at a tolerance (direct joints: kDirectTolerance of the strength)
            // leaves two forces of one joint up to twice that apart with nothing happening (the
            // pieces of a resting object), which is not a load. After fine steps only the load the
            // probe's force has counts, not what it lost: fine and coarse steps share a resting
            // object's weight differently between its joints and its contacts, and its joints can
            // drop from a tenth of their strength to nothing between the two with nothing
            // happening (docs/physics.md section 7a).
            const double change = (f - before_[c]).norm();
            const double counted = block_fine_ ? std::min(change, f.norm()) : change;
            const double df = std::max(0.0, counted - 2 * world_.joint_tolerance() * s);
            spring_load_ = std::max(spring_load_, over(spring, s));
            const double sudden = df > 0 ? std::min(omega_h * df, world_.velocity_jump_force(c, start)) : 0.0;
            other_load_ = std::max(other_load_, over(std::max(f.norm(), sudden), s));
        }
        return std::max(spring_load_, other_load_);
    }

    // The books at the end of a frame; the residual is the frame's largest (and starts again).
    EnergySample books() {
        const BulletWorld::StepWork w = world_.step_work();
        const EnergySample e{world_.time(),        world_.kinetic_energy(), world_.potential_energy(),
                             world_.stored_energy(), injected_,              removed_,
                             world_.elastic_energy(), frame_residual_,       w.joints,
                             w.contacts,             w.driven,               w.integration};
        frame_residual_ = 0;
        return e;
    }

private:
    // kOverlapBreak: adds to `over` (ascending by constraint) the joints still holding a partly
    // joined pair one of whose broken joints' pivots, each carried by its piece, have passed into
    // each other along the line between the pieces' centres by more than kOverlapBreak of the
    // smaller piece's radius beyond what the joints left are pressed together along it (that
    // excess into overlap_). The stretch d = (pivot on B) - (pivot on A) of a joint is how its
    // pivots have parted; -d . (centre of B - centre of A), over that line's length, how far B's
    // pivot went into A. A pair pressed together as a whole (its joints left squeezed as much as
    // the broken ones) is the joints' business, not this rule's: only a turn that the joints left
    // let through counts.
    void add_overlapped(std::vector<Overload>& over) {
        for (size_t c : overlapped_) overlap_[c] = 0;
        overlapped_.clear();
        if (partly_joined_.empty()) return;
        overlap_.resize(world_.constraint_count(), 0.0);
        const size_t loaded = over.size();  // ascending: searched as added ones go to the end
        size_t kept = 0;
        for (const uint32_t p : partly_joined_) {
            const std::vector<size_t>& joints = pair_joints_[p];
            double deepest = 0, pressed = 0;
            bool held = false;
            for (size_t c : joints) {
                const Vec3 line = world_.piece_position(world_.piece_b(c)) - world_.piece_position(world_.piece_a(c));
                if (!(line.norm() > 0)) continue;
                const double depth = -world_.joint_stretch(c).stretch.dot(line) / line.norm();
                if (world_.active(c)) held = true, pressed = std::max(pressed, depth);
                else deepest = std::max(deepest, depth);
            }
            if (!held) continue;  // its last joints broke: no longer partly joined
            partly_joined_[kept++] = p;
            const uint32_t a = world_.piece_a(joints[0]), b = world_.piece_b(joints[0]);
            const double excess = deepest - pressed;
            if (!(excess > kOverlapBreak * std::min(radius_[a], radius_[b]))) continue;
            for (size_t c : joints) {
                if (!world_.active(c)) continue;
                const auto loaded_end = over.begin() + std::ptrdiff_t(loaded);
                const auto at = std::lower_bound(over.begin(), loaded_end, c,
                                                 [](const Overload& o, size_t x) { return o.constraint < x; });
                if (at != loaded_end && at->constraint == c) continue;  // breaks by its load anyway
                overlap_[c] = excess;
                overlapped_.push_back(c);
                const double s = world_.strength(c);
                over.push_back({c, s > 0 ? world_.force_on_a(c).norm() / s : INFINITY});
            }
        }
        partly_joined_.resize(kept);
        if (over.size() > loaded)
            std::sort(over.begin(), over.end(), [](const Overload& x, const Overload& y) { return x.constraint < y.constraint; });
    }

    void energize_break(size_t c, const std::array<BodyAtPivot, 2>& load, const Vec3& frame,
                        const BulletWorld::JoinedPieces* joined, SimulationResult& out) {
        const auto start = std::chrono::steady_clock::now();
        // The energy held by earlier breaks whose two pieces this one parts: one on each side, or
        // one on either side and the other not joined to it any more (the two sides are the
        // fragments of the break's pieces), which the step's breaks did together, none of them
        // with the two on its two sides. Only a pair the step's breaks split can be one.
        double release = 0;
        std::vector<size_t> parted;  // indices into held_
        if (joined && joined->parted) {
            const uint32_t side[2] = {fragments_.of[joined->pieces[0]], fragments_.of[joined->pieces[joined->side_b]]};
            for (size_t h : split_held_) {
                if (held_[h].released) continue;
                const uint32_t a = fragments_.of[held_[h].piece_a], b = fragments_.of[held_[h].piece_b];
                if (a == side[0] || a == side[1] || b == side[0] || b == side[1]) parted.push_back(h), release += held_[h].energy;
            }
        }
        BreakRecord r = energize_broken(world_, c, load, energize_, break_key(in_.simulate.seed, c), frame, joined, release);
        if (r.released_energy > 0)
            for (size_t h : parted) held_[h].released = true;  // taken out after the step's breaks
        if (r.held_energy > 0) {
            held_.push_back({r.piece_a, r.piece_b, r.held_energy});
            if (joined && split(held_.back())) split_held_.push_back(held_.size() - 1);
        }
        r.step = world_.h();
        out.energize_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        injected_ += r.injected_energy + r.momentum_work;
        // What leaves the elastic column: the joint's energy by its stretch (equal to E = |f|^2 / 2k
        // when its force matches its stretch).
        removed_ += 0.5 * world_.stiffness(c) * world_.joint_stretch(c).stretch.squaredNorm();
        out.breaks.push_back(r);
    }

    const SimulationInput& in_;
    BulletWorld& world_;
    const std::vector<double>& radius_;
    // The pairs of pieces the joints join: each joint's pair, each pair's joints (ascending), and
    // the pairs that some of their joints still hold after others broke (ascending).
    std::vector<uint32_t> pair_of_;
    std::vector<std::vector<size_t>> pair_joints_;
    std::vector<uint32_t> partly_joined_;
    std::vector<double> overlap_;  // per joint: the depth that breaks it this step (kOverlapBreak; unit: m)
    std::vector<size_t> overlapped_;  // the joints overlap_ holds a depth for
    BreakPolicy policy_;
    EnergizeSettings energize_;
    BulletWorld::Fragments fragments_;  // after_step's scratch: the fragments its breaks leave
    double injected_ = 0, removed_ = 0;
    double frame_residual_ = 0;
    // Energy held by breaks whose pieces the joints still hold together, until a break parts them.
    struct Held {
        uint32_t piece_a, piece_b;
        double energy;  // (unit: J)
        bool released = false;
    };
    std::vector<Held> held_;
    // After a step's removals: held_'s entries whose two pieces are in two fragments (ascending).
    std::vector<size_t> split_held_;
    bool split(const Held& h) const { return fragments_.of[h.piece_a] != fragments_.of[h.piece_b]; }
    std::vector<Vec3> before_;  // the joints' forces before a probe step
    // The last probe's largest load over strength by the joints' stretch (spring_load_) and by
    // everything else (other_load_: the solver's force, omega h |df|, approaching contacts).
    double spring_load_ = 0, other_load_ = 0;
    std::vector<Vec3> block_impulse_;  // (unit: N s)
    double block_time_ = 0;            // (unit: s)
    bool block_fine_ = false;
};

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

}  // namespace

uint32_t auto_split(double block, double highest, double lowest, bool direct_joints, double max_cfm) {
    if (!(highest > 0)) return 1;
    uint32_t n = 1;
    while (n < kAutoMaxSplit && highest * block / n > kAutoOmegaH) n *= 2;
    // Iterative joints converge only while CFM = 1 / (omega h)^2 <= max_cfm for the softest row
    // (docs/physics.md section 7): h >= 1 / (omega sqrt(max_cfm)).
    if (!direct_joints && lowest > 0)
        while (n > 1 && lowest * (block / n) * std::sqrt(max_cfm) < 1) n /= 2;
    return n;
}

namespace {

// The most any dynamic piece moves for its size, |v| / r + |w| (unit: 1/s), and which piece (in
// *piece); -1 when there is none.
double most_moving(const BulletWorld& world, const std::vector<double>& radius, uint32_t* piece) {
    double most = -1;
    for (uint32_t i = 0; i < world.pieces(); ++i) {
        if (!world.piece_dynamic(i) || !(radius[i] > 0)) continue;
        const double m = world.piece_velocity(i).norm() / radius[i] + world.piece_angular_velocity(i).norm();
        if (m > most) most = m, *piece = i;
    }
    return most;
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

}  // namespace

double rest_speed_landed(const Model& model) {
    Eigen::AlignedBox3d box;
    for (const Piece& p : model.pieces)
        for (const Vec3& v : p.surface.vertices) box.extend(v);
    if (box.isEmpty()) return kRestSpeed;
    return std::max(kRestSpeed, kRestSpeedPerSize * box.diagonal().norm());
}

double rest_speed(const Model& model, double gravity) {
    return std::max(kRestSpeed, std::min(rest_speed_landed(model), kRestFall * gravity * kRestHold));
}

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

bool solves_joints_directly(const Model& model, const SimulateSettings& s) {
    if (s.joints != JointSolve::Auto) return s.joints == JointSolve::Direct;
    return model.pieces.size() <= kAutoDirectPieces;
}

uint32_t frame_count(const SimulateSettings& s) {
    return uint32_t(std::llround((s.auto_duration ? s.max_duration : s.duration) * s.fps)) + 1;
}

SimulationResult simulate(const Model& model, const SimulationInput& shot_input, const std::string& model_id) {
    // With substeps = "auto" the world starts at the coarsest step, a whole block (the CFM check
    // and stiffen then hold for every step the run takes: auto_split keeps the fine ones within
    // max_cfm).
    const uint32_t blocks = uint32_t(std::max(1.0, std::ceil(1.0 / (shot_input.simulate.fps * kAutoBlock) - 1e-9)));
    const double block = 1.0 / (shot_input.simulate.fps * blocks);
    const double h = shot_input.simulate.auto_substeps ? block : 1.0 / (shot_input.simulate.fps * shot_input.simulate.substeps);
    const bool bullet_impulse = shot_input.simulate.break_criterion == BreakCriterion::BulletImpulse;
    SimulationInput in = shot_input;
    // Direct joints solve every joint row exactly whatever its CFM: no stiffness is too soft for
    // the step (docs/physics.md section 5b), so neither stiffen nor the CFM check applies.
    const bool direct = solves_joints_directly(model, in.simulate);
    nlohmann::ordered_json chosen = nlohmann::ordered_json::array();  // logged, and kept in the trajectory
    std::vector<std::string> warned;                                   // the same
    const auto choose = [&](const std::string& what, const std::string& why) {
        spdlog::info("auto: {} ({})", what, why);
        chosen.push_back({{"what", what}, {"why", why}});
    };
    const bool auto_joints = in.simulate.joints == JointSolve::Auto && !model.constraints.empty();
    if (auto_joints && direct) {
        choose("[simulate] joints = \"direct\"",
               fmt::format("{} pieces: direct up to {}", model.pieces.size(), kAutoDirectPieces));
    } else if (auto_joints) {
        // Iterative joints kept for a large model: said with the ratios where they start to fail.
        uint32_t heavy = 0, light = 0, island_heavy = 0, island_light = 0;
        const double ratio = largest_joined_mass_ratio(model, &heavy, &light);
        const double island = largest_island_mass_ratio(model, &island_heavy, &island_light);
        if (ratio <= kIterativeMassRatio && island <= kIterativeIslandRatio) {
            choose("[simulate] joints = \"iterative\"",
                   fmt::format("{} pieces: iterative above {}, where direct joints cost 2 to 5 times as much; the "
                               "largest mass ratio between joined pieces is {:.3g}, piece {} over piece {} "
                               "(iterative joints hold up to {:g}); within an island of joined pieces {:.3g}, piece "
                               "{} over piece {} (up to {:g})",
                               model.pieces.size(), kAutoDirectPieces, ratio, heavy, light, kIterativeMassRatio,
                               island, island_heavy, island_light, kIterativeIslandRatio));
        } else {
            const bool joined = ratio > kIterativeMassRatio;
            warn_and_keep(warned,
                          fmt::format("simulate: joints = \"auto\" keeps iterative joints for {} pieces (direct up to "
                                      "{}), but piece {} is {:.3g} times as heavy as piece {} {}: iterative joints may "
                                      "break or drift apart where they should hold from a mass ratio of {:g} "
                                      "(docs/accuracy.md, \"The stability map\"). [simulate] joints = \"direct\" "
                                      "holds them, at about 2 to 5 times the simulation's time at 100 to 1,000 pieces",
                                      model.pieces.size(), kAutoDirectPieces, joined ? heavy : island_heavy,
                                      joined ? ratio : island, joined ? light : island_light,
                                      joined ? "joined to it" : "in its island of joined pieces",
                                      joined ? kIterativeMassRatio : kIterativeIslandRatio));
        }
    }
    if (in.material.stiffen && !direct) {
        // A stiffness too soft for the step (pieces smaller or heavier than the shot was tuned
        // for) is raised to the least that converges, with a margin, instead of refused; the
        // trajectory's settings then hold the stiffness used.
        size_t first = 0;
        const double need = least_stiffness(BulletWorld(model, {in.scene, in.object, in.material, h,
                                                                 in.simulate.iterations, bullet_impulse}),
                                            model, in, &first);
        if (need > 0) {
            const double stiffness = 1.05 * need;
            choose(fmt::format("{} {:.4g} -> {:.4g} {}", stiffness_number_key(in.material), stiffness_number(in.material),
                               stiffness, stiffness_number_unit(in.material)),
                   fmt::format("constraint {} would need CFM above {:g} at h = {:.4g} s; [material] stiffen = true", first,
                               in.simulate.max_cfm, h));
            set_stiffness_number(in.material, stiffness);
        }
    }
    WorldSetup setup{in.scene, in.object, in.material, h, in.simulate.iterations, bullet_impulse};
    setup.direct_joints = direct;
    setup.rigid_flight = in.simulate.rigid_flight;
    if (in.simulate.sleep) setup.sleep_speed = kSleepSpeed;
    setup.threads = in.threads;
    BulletWorld world(model, setup);
    if (!direct) check_cfm(world, model, in);

    double stiffest = 0, softest = 0;  // (unit: rad/s)
    world.joint_frequencies(&stiffest, &softest);

    SimulationResult out;
    out.warnings = std::move(warned);
    Trajectory& t = out.trajectory;
    t.producer = producer_string();
    t.fps = in.simulate.fps;
    t.pieces = world.pieces();
    t.props = world.props();
    std::vector<double> radius(world.pieces(), 0.0);
    for (uint32_t i = 0; i < world.pieces() && i < model.pieces.size(); ++i) radius[i] = piece_radius(model.pieces[i]);
    Run run(in, world, radius);
    InstabilityGuard guard(world, model, in.scene, in.object, in.material);
    record(world, t);
    out.energy.push_back(run.books());

    const uint32_t frames = frame_count(in.simulate);
    // duration = "auto": each piece's centre between two recorded frames against the rest speed,
    // and how far its farthest point got from where it was at the hold's first frame (|dx| +
    // angle r) against the rest speed times the hold. The recorded motion, not the velocities of
    // the frame's last step, and the turn over the hold, not between two frames: a piece resting
    // on others trembles in place (measured on the demo: a piece turning back and forth at 0.2
    // rad/s for 2 s, 0.14 degrees in all).
    // Until the object first touches the scene (or breaks), the rest speed is capped by the fall
    // (rest_speed); from then on it is the object's own (rest_speed_landed): a 600 m object
    // whose last piece slides at 6 m/s moves under half a pixel a frame in a movie that frames it.
    // The hold then begins no earlier than the frame it landed in: the fall before it does not count.
    // (substeps = "auto" spans blocks only from then on too.)
    double rest = rest_speed(model, in.scene.gravity.norm());
    bool landed = false;
    uint32_t hold_from = 0, frame = 0;
    const uint32_t hold_frames = uint32_t(std::ceil(kRestHold * in.simulate.fps - 1e-9));
    // Every dynamic piece stayed within reach of its pose at frame `from` up to frame `to`.
    // A piece far from the others may move faster and still look still: a camera that keeps it in
    // view stands at least its distance d from the pieces' centre away (fov 40 degrees), where
    // kRestSpeedPerSize x d moves it under half a pixel a frame, and one that lets it go does not
    // see it. So each piece rests below the larger of the rest speed and kRestSpeedPerSize times its
    // distance from the dynamic pieces' centre of mass (a ball rolled 24 m from a 0.3 m object
    // ends its movie when the object's other pieces rest, not seconds later).
    std::vector<double> mass(world.pieces(), 0.0);
    for (uint32_t i = 0; i < world.pieces() && i < model.pieces.size(); ++i)
        if (world.piece_dynamic(i)) mass[i] = model.pieces[i].mass.mass;
    auto centre = [&](uint32_t g) {
        Vec3 c = Vec3::Zero();
        double m = 0;
        for (uint32_t i = 0; i < world.pieces(); ++i) c += mass[i] * t.pose(g, i).position.cast<double>(), m += mass[i];
        return m > 0 ? Vec3(c / m) : c;
    };
    // And no piece may gather speed over the hold (by more than kRestSpeed from its first frame to
    // its last): an object of hundreds of metres collapses under its own weight slowly at first,
    // below its size's rest speed.
    auto speed = [&](uint32_t g, uint32_t i) {
        return (t.pose(g, i).position - t.pose(g - 1, i).position).cast<double>().norm() * in.simulate.fps;
    };
    // Once landed, the rest speed grows with the pieces' spread as it grows with the object's size:
    // a camera that frames pieces strewn over 2 m (the follow camera frames the 90% of the mass
    // nearest its middle) sees a fragment creep at 5 cm/s under half a pixel a frame.
    std::vector<std::pair<double, double>> by_distance;  // (distance from the centre, mass)
    auto spread = [&](uint32_t g, const Vec3& c) {
        by_distance.clear();
        double total = 0;
        for (uint32_t i = 0; i < world.pieces(); ++i)
            if (mass[i] > 0) by_distance.emplace_back((t.pose(g, i).position.cast<double>() - c).norm(), mass[i]), total += mass[i];
        std::sort(by_distance.begin(), by_distance.end());
        double held = 0;
        for (const auto& [d, m] : by_distance)
            if ((held += m) >= kRestSpreadMass * total) return 2 * d;
        return 0.0;
    };
    auto stayed = [&](uint32_t from, uint32_t to) {
        std::vector<Vec3> centres;
        std::vector<double> rests;
        for (uint32_t g = from; g <= to; ++g) {
            centres.push_back(centre(g));
            rests.push_back(landed ? std::max(rest, kRestSpeedPerSize * spread(g, centres.back())) : rest);
        }
        for (uint32_t i = 0; i < world.pieces(); ++i) {
            if (!world.piece_dynamic(i)) continue;
            if (to > from + 1 && speed(to, i) > speed(from + 1, i) + kRestSpeed) return false;
            const BodyPose& a = t.pose(from, i);
            for (uint32_t g = from + 1; g <= to; ++g) {
                const BodyPose& b = t.pose(g, i);
                const double own = std::max(rests[g - from], kRestSpeedPerSize * (b.position.cast<double>() - centres[g - from]).norm());
                if (!(speed(g, i) < own)) return false;
                const double angle = 2 * std::acos(std::min(1.0, std::abs(double(a.rotation.dot(b.rotation)))));
                if (!((b.position - a.position).cast<double>().norm() + angle * radius[i] < own * kRestHold)) return false;
            }
        }
        return true;
    };
    Progress progress("simulate", frames - 1);
    bool fine = false;     // substeps = "auto": the next block runs in fine steps
    uint32_t coarse = 1;   // and otherwise in this many steps
    // Whether the object hit something: its first contact with the scene came after its first
    // step (an object that starts resting on the ground, the chain, hit nothing by that).
    bool touched = false, hit = false;
    auto after_step = [&] {
        guard.after_step(world);
        if (!touched && world.touches_scene()) touched = true, hit = out.steps > 1;
        if (!landed && (in.simulate.auto_duration || in.simulate.auto_substeps) &&
            (!out.breaks.empty() || touched)) {
            landed = true;
            rest = rest_speed_landed(model);
            hold_from = frame;
        }
        return check_stability(world, guard, run.injected(), in.simulate.on_instability, out);
    };
    // How many blocks (a power of two, at most kAutoMaxSpan) the next probe may span after a kept
    // step of `now` blocks: as many as keep the loads of that step, scaled to the longer one (the
    // stretch as h^2, everything else as h), under kAutoRefineLoad, and every awake piece's travel
    // within the step under kAutoSpanTravel of its size.
    uint32_t span = 1;
    uint32_t waits = 0, backoff = 1;  // blocks to run fine unprobed, and the next such wait
    auto calm_span = [&](uint32_t now) {
        uint32_t fastest = 0;
        const double travel = std::max(0.0, most_moving(world, radius, &fastest));  // per second, over size
        uint32_t next = std::min(2 * now, kAutoMaxSpan);
        while (next > 1) {
            const double r = double(next) / now;
            if (run.spring_load() * r * r < kAutoRefineLoad && run.other_load() * r < kAutoRefineLoad &&
                travel * next * block < kAutoSpanTravel)
                break;
            next /= 2;
        }
        return next;
    };
    // The fine steps per block (auto_split) for the joints as they are now.
    auto fine_split = [&] {
        double highest = 0, lowest = 0;
        world.joint_frequencies(&highest, &lowest);
        return auto_split(block, highest, lowest, direct, in.simulate.max_cfm);
    };
    for (uint32_t f = 1; f < frames && out.complete; ++f) {
        frame = f;
        if (!in.simulate.auto_substeps) {
            for (uint32_t s = 0; s < in.simulate.substeps; ++s) {
                run.substep(out);
                if (!after_step()) break;
            }
        } else {
            for (uint32_t b = 0; b < blocks && out.complete; ++b) {
                // Waiting out a stretch that the fine steps resolve and a split would not (below).
                const bool wait = !fine && waits > 0;
                if (wait) --waits;
                // Calm, once the object has touched the scene: one probe over `span` blocks,
                // aligned within the frame (before, the fall keeps the blocks' step, so that an
                // impact comes when a fixed step of a block's length has it).
                uint32_t over = fine || wait || coarse > 1 || !landed ? 1 : span;
                while (over > 1 && (b % over != 0 || b + over > blocks)) over /= 2;
                if (over > 1) {
                    if (run.probe(out, block * over)) {
                        run.start_block(false);
                        run.add_to_block();
                        b += over - 1;
                        if (!after_step()) break;
                        span = calm_span(over);
                        continue;
                    }
                }
                span = 1;
                const size_t breaks = out.breaks.size();
                double peak = 0;
                // Not fine: the block in `split` steps (coarse, the split kept last), each a probe.
                uint32_t split = 1, kept = 0;
                uint32_t n = 0;  // the fine steps per block, once needed
                if (!fine && !wait) {
                    split = coarse;
                    double stretch = 0;  // the kept steps' largest spring load
                    while (kept < split) {
                        if (!run.probe(out, block / split)) {
                            // Refused: the rest of the block in shorter steps, where only the
                            // joints' stretch refused it.
                            n = fine_split();
                            const uint32_t finer = split * run.finer_split();
                            if (finer >= n && finer > split) {
                                // Refused for its stretch alone, which only the fine steps
                                // resolve: the next 1, 2, 4, then 8 blocks go to them unprobed.
                                waits = backoff;
                                backoff = std::min(2 * backoff, kAutoMaxWait);
                            }
                            if (finer == split || finer >= n) break;
                            kept *= finer / split;
                            split = finer;
                            continue;
                        }
                        if (kept == 0) run.start_block(split > 1);
                        run.add_to_block();
                        stretch = std::max(stretch, run.spring_load());
                        ++kept;
                        if (!after_step()) break;
                    }
                    if (!out.complete) break;
                    if (kept == split) {
                        // All kept: the next block probes again, in as many steps, or half as many
                        // when the stretch, which grows as the square of the step, allows.
                        coarse = split > 1 && 4 * stretch < kAutoRefineLoad ? split / 2 : split;
                        if (split == 1) span = calm_span(1);
                        backoff = 1;
                        continue;
                    }
                    coarse = 1;
                }
                // The rest of the block in fine steps.
                if (kept == 0) run.start_block(true);
                n = std::max(n ? n : fine_split(), split);
                world.set_step(block / n);
                const uint32_t left = (split - kept) * (n / split);
                for (uint32_t s = 0; s < left; ++s) {
                    run.substep(out);
                    run.add_to_block();
                    peak = std::max(peak, world.max_load());
                    if (!after_step()) break;
                }
                fine = !(peak < kAutoCalmLoad && out.breaks.size() == breaks);
            }
        }
        if (!out.complete) break;
        record(world, t);
        out.energy.push_back(run.books());
        progress.advance();
        if (in.simulate.auto_duration && f >= hold_from + hold_frames && stayed(f - hold_frames, f)) {
            out.rest_time = (f - hold_frames) / in.simulate.fps;
            break;
        }
    }
    t.complete = out.complete;
    out.asleep = world.sleeping_pieces();
    out.parallel_contact_tests = world.parallel_contact_tests();
    if (in.simulate.auto_duration && out.complete && out.rest_time < 0) warn_still_moving(world, radius, in.simulate, out.warnings);
    if (out.deepest.depth_per_radius > kDeepContactWarning) {
        // A step 2^k times shorter, k enough to bring the depth under half the radius were it in
        // proportion to the step (it falls less: docs/log.md, 2026-11-30).
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
    if (out.breaks.empty() && hit && !in.simulate.auto_substeps && stiffest * h > kStiffStepWarning)
        warn_and_keep(out.warnings,
             fmt::format("simulate: no joint broke, and at this step (h = {:.3g} s) the stiffest joint has omega h = "
                         "{:.0f}: an impact's peak force is resolved to about 1/{:.0f} of itself (docs/physics.md "
                         "section 7). For a stiff material, [simulate] substeps = \"auto\" and joints = \"direct\" "
                         "resolve it (glmark2's bunny in porcelain, dropped 1.5 m: 59 breaks, 11 s for the whole job)",
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
    // The settings last: they keep every warning of the run.
    t.settings_json = trajectory_settings(in, model_id, model, chosen, out.warnings);
    return out;
}

}  // namespace shatter
