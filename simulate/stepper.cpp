#include "simulate/stepper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>

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

}  // namespace

Stepper::Stepper(const SimulationInput& in, BulletWorld& world, const std::vector<double>& radius)
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

void Stepper::substep(SimulationResult& out) {
    std::shared_ptr<BulletWorld::Snapshot> start;
    if (in_.simulate.rollback) start = world_.save();
    world_.step();
    after_step(out, start);
}

bool Stepper::probe(SimulationResult& out, double h) {
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

void Stepper::after_step(SimulationResult& out, const std::shared_ptr<BulletWorld::Snapshot>& start) {
    const ResidualPeak now = measure(out);
    const std::vector<size_t> broken = pick_breaks(out, now);
    if (broken.empty()) return;
    // The load at the break defines E and the directions; a rollback re-runs the step without
    // the broken constraints, and the impulses then act on the re-run state.
    std::vector<std::array<BodyAtPivot, 2>> loads;
    for (size_t c : broken) {
        Vec3 pivot;
        loads.push_back(world_.bodies_at_pivot(c, &pivot));
    }
    roll_back_or_remove(broken, start);
    energize_breaks(broken, loads, out);
}

// The step's residual (kept for the frame and the run) and deepest contact.
ResidualPeak Stepper::measure(SimulationResult& out) {
    ++out.steps;
    out.solver_iterations += uint64_t(world_.last_step_iterations());
    int64_t worst = -1;
    const double r = world_.max_joint_residual(&worst);
    frame_residual_ = std::max(frame_residual_, r);
    if (r > out.residual.residual) out.residual = {r, world_.time(), worst};
    const DeepContact deep = world_.last_step_deepest_contact();
    if (deep.depth_per_radius > out.deepest.depth_per_radius)
        out.deepest = deep, out.deepest_time = world_.time(), out.deepest_step = world_.h();
    return {r, world_.time(), worst};
}

// The joints that break after this step (ascending); until the first break, the residual before it.
std::vector<size_t> Stepper::pick_breaks(SimulationResult& out, const ResidualPeak& now) {
    std::vector<Overload> over = find_overloads(world_, in_.simulate.break_criterion);
    add_overlapped(over);
    std::vector<size_t> broken = policy_.select(over, world_.time());
    if (broken.empty() && out.breaks.empty() && now.residual > out.residual_before_break.residual)
        out.residual_before_break = now;
    return broken;
}

void Stepper::roll_back_or_remove(const std::vector<size_t>& broken, const std::shared_ptr<BulletWorld::Snapshot>& start) {
    if (start) world_.restore(*start);
    for (size_t c : broken) world_.remove_constraint(c);
    if (start) world_.step();
}

void Stepper::energize_breaks(const std::vector<size_t>& broken, const std::vector<std::array<BodyAtPivot, 2>>& loads,
                              SimulationResult& out) {

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

uint32_t Stepper::finer_split() const {
    if (!(other_load_ < kAutoRefineLoad) || !std::isfinite(spring_load_)) return 1;
    uint32_t m = 2;
    while (m < kAutoMaxSplit && !(spring_load_ / (double(m) * m) < kAutoRefineLoad)) m *= 2;
    return m;
}

void Stepper::start_block(bool fine) {
    block_impulse_.assign(world_.constraint_count(), Vec3::Zero());
    block_time_ = 0;
    block_fine_ = fine;
}

void Stepper::add_to_block() {
    const double h = world_.h();
    for (size_t c = 0; c < block_impulse_.size(); ++c)
        if (world_.active(c)) block_impulse_[c] += h * world_.force_on_a(c);
    block_time_ += h;
}

double Stepper::impact_load(const BulletWorld::Snapshot& start) {
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

EnergySample Stepper::books() {
    const BulletWorld::StepWork w = world_.step_work();
    const EnergySample e{world_.time(),        world_.kinetic_energy(), world_.potential_energy(),
                         world_.stored_energy(), injected_,              removed_,
                         world_.elastic_energy(), frame_residual_,       w.joints,
                         w.contacts,             w.driven,               w.integration};
    frame_residual_ = 0;
    return e;
}

void Stepper::add_overlapped(std::vector<Overload>& over) {
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
            over.push_back({c, s > 0 ? world_.load_on_a(c).norm() / s : INFINITY});
        }
    }
    partly_joined_.resize(kept);
    if (over.size() > loaded)
        std::sort(over.begin(), over.end(), [](const Overload& x, const Overload& y) { return x.constraint < y.constraint; });
}

void Stepper::energize_break(size_t c, const std::array<BodyAtPivot, 2>& load, const Vec3& frame,
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

}  // namespace shatter
