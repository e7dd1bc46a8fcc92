// The energy books through a break (simulate/simulate.h, EnergySample): kinetic + potential +
// elastic + removed + joints_damped + contacts + integration - injected - driven stays constant,
// each term measured on its own (the pieces' motion and height, the joints' stretch, each joint's
// and contact's impulse on its bodies' mean velocity, the drives' work, gravity's integration). On the chain the joints that
// do not break hold ten times the broken one's energy and lose it to the implicit step within a
// millisecond of the break: without the joints' column the books would miss it.
#include <gtest/gtest.h>

#include <algorithm>

#include "scene_support.h"

namespace shatter {
namespace {

using namespace scenes_test;

double books(const EnergySample& e) {
    return e.kinetic + e.potential + e.elastic + e.removed + e.joints_damped + e.contacts + e.integration - e.injected -
           e.driven;
}

struct Spread {
    double books = 0;            // the books' range around the first break (unit: J)
    double without_joints = 0;   // the same without the joints' column (unit: J)
    double without_integration = 0;  // the same without the integration column (unit: J)
    double stored = 0;           // the stored energy of the breaks (unit: J)
    double removed = 0;          // what the broken joints held by their stretch, at the end (unit: J)
};

// The books' range from 0.1 s before the first break to 0.1 s after it.
Spread books_around_first_break(const SimulationResult& r) {
    Spread s;
    for (const BreakRecord& b : r.breaks) s.stored += b.kicks.stored_energy;
    const double t = r.breaks.front().time;
    double lo = 1e300, hi = -1e300, lo_j = 1e300, hi_j = -1e300, lo_i = 1e300, hi_i = -1e300;
    for (const EnergySample& e : r.energy) {
        if (std::abs(e.time - t) > 0.1) continue;
        lo = std::min(lo, books(e)), hi = std::max(hi, books(e));
        lo_j = std::min(lo_j, books(e) - e.joints_damped), hi_j = std::max(hi_j, books(e) - e.joints_damped);
        lo_i = std::min(lo_i, books(e) - e.integration), hi_i = std::max(hi_i, books(e) - e.integration);
    }
    s.books = hi - lo, s.without_joints = hi_j - lo_j, s.without_integration = hi_i - lo_i;
    s.removed = r.energy.back().removed;
    return s;
}

TEST(EnergyBooks, TheChainsBooksCloseThroughItsBreak) {
    const Shot shot = asset("chain");
    const Model model = prescore_shot(shot, nullptr);
    for (double alpha : {0.0, 1.0}) {
        const SimulationResult r = simulate(model, input_of(shot, alpha, 0.45), "chain");
        ASSERT_FALSE(r.breaks.empty());
        const Spread s = books_around_first_break(r);
        EXPECT_LT(s.books, 1e-6 * s.stored) << "alpha " << alpha;  // round-off: measured 2e-8
        EXPECT_GT(s.without_joints, 5 * s.stored) << "alpha " << alpha;
        // The drives did the work the joints stored and then lost.
        EXPECT_GT(r.energy.back().driven, 5 * s.stored);
    }
}

// A shot at alpha 1 for `duration` seconds: its breaks and books around the first.
Spread books_of(const Shot& shot, double duration, size_t* breaks) {
    const SimulationResult r = simulate(prescore_shot(shot, nullptr), input_of(shot, 1.0, duration), "books");
    *breaks = r.breaks.size();
    return r.breaks.empty() ? Spread{} : books_around_first_break(r);
}

TEST(EnergyBooks, TheBeamsBooksCloseThroughItsBreaks) {
    size_t breaks = 0;
    const Spread s = books_of(asset("beam"), 0.45, &breaks);
    ASSERT_EQ(breaks, 4u);
    EXPECT_LT(s.books, 1e-6 * s.stored);  // round-off: measured 3e-9
}

// 360 breaks in 86 ms as the plate lands on the sphere, its cubes rolling and spinning on it and on
// each other: the contacts' rolling and spinning friction booked with the sliding friction.
TEST(EnergyBooks, ThePlatesBooksCloseThroughItsImpact) {
    size_t breaks = 0;
    const Spread s = books_of(asset("plate"), 0.45, &breaks);
    ASSERT_GT(breaks, 300u);
    EXPECT_LT(s.books, 1e-6 * s.stored);  // round-off: measured 2e-8
}

// The demo: the bunny falls as one body (rigid flight), on the parabola exactly, so the
// integration column books nothing until it lands (bullet_world.h, StepWork::integration; the
// solver's own update, x += v h, would take M |g|^2 h^2 / 2 a step of 1/480 s: 0.127 J/s for its
// 1.2666 kg). Its joints are solved directly, so a breaking joint's stretch holds what its force
// stores, k |d|^2 / 2 = |f|^2 / (2 k): summed over the breaks, within 20%.
TEST(EnergyBooks, TheDemoBunnysBooksCloseThroughItsImpact) {
    const Shot shot = asset("bunny");
    const Model model = prescore_shot(shot, nullptr);
    const SimulationResult r = simulate(model, input_of(shot, 1.0, 1.0), "books");
    ASSERT_GT(r.breaks.size(), 200u);
    const Spread s = books_around_first_break(r);
    EXPECT_LT(s.books, 1e-6 * s.stored);  // round-off: measured 7e-14 J of 2.04 J
    EXPECT_NEAR(s.removed, s.stored, 0.2 * s.stored);
    // The samples of the flight before the first break (the landing starts within its frame).
    const double t_break = r.breaks.front().time;
    size_t flight = 0;
    for (const EnergySample& e : r.energy)
        if (e.time < t_break - 1.0 / 30) {
            EXPECT_EQ(e.integration, 0.0) << "at " << e.time;
            ++flight;
        }
    EXPECT_GT(flight, 10u);
}

// A real mesh with the defaults (`shatter run MESH`): glmark2-data's horse, whose fragments spin,
// slide and are pushed out of the ground after its impact.
TEST(EnergyBooks, ARealMeshsBooksCloseWithTheDefaults) {
    size_t breaks = 0;
    const Spread s = books_of(default_shot_for_mesh("/usr/share/glmark2/models/horse.3ds"), 1.0, &breaks);
    ASSERT_GT(breaks, 100u);
    EXPECT_LT(s.books, 1e-5 * s.stored);                // round-off: measured 6e-7
    EXPECT_GT(s.without_integration, 0.01 * s.stored);
}

}  // namespace
}  // namespace shatter
