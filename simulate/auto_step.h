// The automatic step (substeps = "auto"; docs/physics.md, "The automatic step"): a frame is cut
// into blocks of at most kAutoBlock, and each block runs as
//   a calm probe over up to kAutoMaxSpan blocks (once the object has touched the scene and the
//     last kept step allows it: calm_span),
//   else a probe of the block in `coarse` steps, each kept when its joints carry less than
//     kAutoRefineLoad of their strength (Stepper::probe),
//   else, from the first refused probe on, the rest of the block in the fine steps the stiffest
//     joint needs (auto_split), and the next block fine too while the loads stay above
//     kAutoCalmLoad or joints break.
// A probe refused for its joints' stretch alone is split (Stepper::finer_split) instead; one that
// only the fine steps resolve sends the next 1, 2, 4 ... kAutoMaxWait blocks to them unprobed.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "simulate/simulate.h"

namespace shatter {

class BulletWorld;
class Stepper;

// The most any dynamic piece moves for its size, |v| / r + |w| (unit: 1/s), and which piece (in
// *piece); -1 when there is none.
double most_moving(const BulletWorld& world, const std::vector<double>& radius, uint32_t* piece);

class AutoStep {
public:
    // `block`: the blocks' length (unit: s); `direct`: whether the joints are solved directly.
    AutoStep(Stepper& run, BulletWorld& world, const std::vector<double>& radius, double block, bool direct,
             double max_cfm);

    // One frame of `blocks` blocks. `after_step` runs after every kept step (false: the run stops,
    // out.complete is false); `landed` tells whether the object has touched the scene (or broken).
    void frame(uint32_t blocks, SimulationResult& out, const std::function<bool()>& after_step, const bool& landed);

private:
    // How many blocks (a power of two, at most kAutoMaxSpan) the next probe may span after a kept
    // step of `now` blocks: as many as keep the loads of that step, scaled to the longer one (the
    // stretch as h^2, everything else as h), under kAutoRefineLoad, and every awake piece's travel
    // within the step under kAutoSpanTravel of its size.
    uint32_t calm_span(uint32_t now) const;
    // The fine steps per block (auto_split) for the joints as they are now.
    uint32_t fine_split() const;

    Stepper& run_;
    BulletWorld& world_;
    const std::vector<double>& radius_;
    const double block_;
    const bool direct_;
    const double max_cfm_;
    bool fine_ = false;     // the next block runs in fine steps
    uint32_t coarse_ = 1;   // and otherwise in this many steps
    uint32_t span_ = 1;     // blocks the next calm probe may span
    uint32_t waits_ = 0, backoff_ = 1;  // blocks to run fine unprobed, and the next such wait
};

}  // namespace shatter
