// The step and what follows it: one solver step, then the step's breaks. A step is a fixed list
// of stages, in this order (simulate.h has the run around it):
//
//   save          the world's state, when the step may be run again (rollback, or a probe the
//                 automatic step may undo)
//   step          one Bullet step of h
//   measure       the joints' residual and the deepest contact, kept for the summary
//   pick breaks   overloaded joints (and joints of pairs turned into each other), through the
//                 break policy
//   roll back     to the saved state and step again without them (rollback), or remove them
//   energize      give each break's alpha E back as kicks, counted in the books
//
// The instability guard and the frame's record come after, in simulate.cpp. The stepper also
// keeps what the automatic step (auto_step.h) reads of a step: the probe's loads and each joint's
// impulse over the current block.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "simulate/break_policy.h"
#include "simulate/breaking.h"
#include "simulate/bullet_world.h"
#include "simulate/simulate.h"

namespace shatter {

class Stepper {
public:
    // `radius`: each piece's (piece_radius; 0 for a prop).
    Stepper(const SimulationInput& in, BulletWorld& world, const std::vector<double>& radius);

    // One step of the world's h, then its breaks.
    void substep(SimulationResult& out);

    // The automatic step's probe: one step of the whole block, kept and processed as any step when
    // every joint carries less than kAutoRefineLoad of its strength; otherwise undone (false).
    // The joints' forces the probe is compared with are their mean forces over the block before it
    // (its impulse over its time): after fine steps, a joint that rings at its own frequency (which
    // a coarse step does not resolve and damps) has the mean of its ringing, not the force of the
    // last fine step.
    // `h` is the probe's length: the block's, or a part of it (the block then in steps of h).
    bool probe(SimulationResult& out, double h);

    double injected() const { return injected_; }  // (unit: J)

    // After a refused probe: by how many times (a power of two) a shorter step may pass the probe's
    // test, or 1 when none may. Only a probe refused for its joints' stretch alone (the solver's
    // forces, their sudden changes and approaching contacts all under kAutoRefineLoad) is split: a
    // step on joined pieces that turn parts their pivots by about (omega h)^2 |r| / 2 (docs/physics.md
    // section 7a), which falls as the square of the step.
    uint32_t finer_split() const;
    double spring_load() const { return spring_load_; }  // the last probe's, over strength
    double other_load() const { return other_load_; }    // the same, by everything else

    // The automatic step's record of a block: each joint's impulse over the block's steps so far,
    // and whether the block is in fine steps.
    void start_block(bool fine);
    void add_to_block();

    // The books at the end of a frame; the residual is the frame's largest (and starts again).
    EnergySample books();

private:
    // The stages after a step (the header's list): a rollback from `start` re-runs it.
    void after_step(SimulationResult& out, const std::shared_ptr<BulletWorld::Snapshot>& start);
    ResidualPeak measure(SimulationResult& out);
    std::vector<size_t> pick_breaks(SimulationResult& out, const ResidualPeak& now);
    void roll_back_or_remove(const std::vector<size_t>& broken, const std::shared_ptr<BulletWorld::Snapshot>& start);
    void energize_breaks(const std::vector<size_t>& broken, const std::vector<std::array<BodyAtPivot, 2>>& loads,
                         SimulationResult& out);

    // The largest load of the probe step over the joints' strength, counting a sudden one at the
    // force the joint would really reach: a change df of a joint's force within a step that treats
    // it as rigid (omega h > 1) stands for a relative velocity jump whose peak force is
    // omega h |df| (docs/physics.md section 7), where the step itself shows only df; no more than
    // the peak force of the jump its bodies' velocities show from `start` to now (a load moved
    // between joints that balance on their bodies, as a slow pull loads a chain, is no impact).
    // Also keeps its two parts (spring_load_, other_load_), of which it is the larger.
    double impact_load(const BulletWorld::Snapshot& start);

    // kOverlapBreak: adds to `over` (ascending by constraint) the joints still holding a partly
    // joined pair one of whose broken joints' pivots, each carried by its piece, have passed into
    // each other along the line between the pieces' centres by more than kOverlapBreak of the
    // smaller piece's radius beyond what the joints left are pressed together along it (that
    // excess into overlap_). The stretch d = (pivot on B) - (pivot on A) of a joint is how its
    // pivots have parted; -d . (centre of B - centre of A), over that line's length, how far B's
    // pivot went into A. A pair pressed together as a whole (its joints left squeezed as much as
    // the broken ones) is the joints' business, not this rule's: only a turn that the joints left
    // let through counts.
    void add_overlapped(std::vector<Overload>& over);

    void energize_break(size_t c, const std::array<BodyAtPivot, 2>& load, const Vec3& frame,
                        const BulletWorld::JoinedPieces* joined, SimulationResult& out);

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

}  // namespace shatter
