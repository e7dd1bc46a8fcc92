#include "simulate/auto_step.h"

#include <algorithm>
#include <cmath>

#include "simulate/bullet_world.h"
#include "simulate/stepper.h"

namespace shatter {

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

double most_moving(const BulletWorld& world, const std::vector<double>& radius, uint32_t* piece) {
    double most = -1;
    for (uint32_t i = 0; i < world.pieces(); ++i) {
        if (!world.piece_dynamic(i) || !(radius[i] > 0)) continue;
        const double m = world.piece_velocity(i).norm() / radius[i] + world.piece_angular_velocity(i).norm();
        if (m > most) most = m, *piece = i;
    }
    return most;
}

AutoStep::AutoStep(Stepper& run, BulletWorld& world, const std::vector<double>& radius, double block, bool direct,
                   double max_cfm)
    : run_(run), world_(world), radius_(radius), block_(block), direct_(direct), max_cfm_(max_cfm) {}

void AutoStep::frame(uint32_t blocks, SimulationResult& out, const std::function<bool()>& after_step, const bool& landed) {
    for (uint32_t b = 0; b < blocks && out.complete; ++b) {
        // Waiting out a stretch that the fine steps resolve and a split would not (below).
        const bool wait = !fine_ && waits_ > 0;
        if (wait) --waits_;
        // Calm, once the object has touched the scene: one probe over `span` blocks,
        // aligned within the frame (before, the fall keeps the blocks' step, so that an
        // impact comes when a fixed step of a block's length has it).
        uint32_t over = fine_ || wait || coarse_ > 1 || !landed ? 1 : span_;
        while (over > 1 && (b % over != 0 || b + over > blocks)) over /= 2;
        if (over > 1) {
            if (run_.probe(out, block_ * over)) {
                run_.start_block(false);
                run_.add_to_block();
                b += over - 1;
                if (!after_step()) break;
                span_ = calm_span(over);
                continue;
            }
        }
        span_ = 1;
        const size_t breaks = out.breaks.size();
        double peak = 0;
        // Not fine: the block in `split` steps (coarse, the split kept last), each a probe.
        uint32_t split = 1, kept = 0;
        uint32_t n = 0;  // the fine steps per block, once needed
        if (!fine_ && !wait) {
            split = coarse_;
            double stretch = 0;  // the kept steps' largest spring load
            while (kept < split) {
                if (!run_.probe(out, block_ / split)) {
                    // Refused: the rest of the block in shorter steps, where only the
                    // joints' stretch refused it.
                    n = fine_split();
                    const uint32_t finer = split * run_.finer_split();
                    if (finer >= n && finer > split) {
                        // Refused for its stretch alone, which only the fine steps
                        // resolve: the next 1, 2, 4, then 8 blocks go to them unprobed.
                        waits_ = backoff_;
                        backoff_ = std::min(2 * backoff_, kAutoMaxWait);
                    }
                    if (finer == split || finer >= n) break;
                    kept *= finer / split;
                    split = finer;
                    continue;
                }
                if (kept == 0) run_.start_block(split > 1);
                run_.add_to_block();
                stretch = std::max(stretch, run_.spring_load());
                ++kept;
                if (!after_step()) break;
            }
            if (!out.complete) break;
            if (kept == split) {
                // All kept: the next block probes again, in as many steps, or half as many
                // when the stretch, which grows as the square of the step, allows.
                coarse_ = split > 1 && 4 * stretch < kAutoRefineLoad ? split / 2 : split;
                if (split == 1) span_ = calm_span(1);
                backoff_ = 1;
                continue;
            }
            coarse_ = 1;
        }
        // The rest of the block in fine steps.
        if (kept == 0) run_.start_block(true);
        n = std::max(n ? n : fine_split(), split);
        world_.set_step(block_ / n);
        const uint32_t left = (split - kept) * (n / split);
        for (uint32_t s = 0; s < left; ++s) {
            run_.substep(out);
            run_.add_to_block();
            peak = std::max(peak, world_.max_load());
            if (!after_step()) break;
        }
        fine_ = !(peak < kAutoCalmLoad && out.breaks.size() == breaks);
    }
}

uint32_t AutoStep::calm_span(uint32_t now) const {
    uint32_t fastest = 0;
    const double travel = std::max(0.0, most_moving(world_, radius_, &fastest));  // per second, over size
    uint32_t next = std::min(2 * now, kAutoMaxSpan);
    while (next > 1) {
        const double r = double(next) / now;
        if (run_.spring_load() * r * r < kAutoRefineLoad && run_.other_load() * r < kAutoRefineLoad &&
            travel * next * block_ < kAutoSpanTravel)
            break;
        next /= 2;
    }
    return next;
}

uint32_t AutoStep::fine_split() const {
    double highest = 0, lowest = 0;
    world_.joint_frequencies(&highest, &lowest);
    return auto_split(block_, highest, lowest, direct_, max_cfm_);
}

}  // namespace shatter
