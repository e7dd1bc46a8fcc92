// The paper's scenes as users run them (assets/*.toml -> prescore_shot -> simulate), shortened:
// each fractures, the energy books balance per break, the energy given back grows with alpha,
// and the chain breaks once and recoils. docs/scenes.md lists the full measurements.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_support.h"

namespace shatter {
namespace {

using namespace scenes_test;

// With exact_energy the impulses are solved so that the pair's kinetic energy rises by exactly
// alpha E (docs/physics.md section 4): the measured rise must match to round-off.
void expect_books_balance(const SimulationResult& r, double alpha) {
    ASSERT_FALSE(r.breaks.empty());
    double stored = 0, injected = 0;
    for (const BreakRecord& b : r.breaks) {
        EXPECT_NEAR(b.injected_energy, alpha * b.kicks.stored_energy, 1e-9 + 1e-6 * alpha * b.kicks.stored_energy)
            << "break of constraint " << b.constraint << " at t = " << b.time;
        stored += b.kicks.stored_energy;
        injected += b.injected_energy;
    }
    EXPECT_NEAR(injected, alpha * stored, 1e-6 * stored + 1e-12);
}

TEST(PaperScenes, EveryGeneratedShotBuildsTheSameBytesTwiceAndRecordsItsSettings) {
    for (const char* name : {"beam", "plate", "chain"}) {
        const Shot shot = asset(name);
        ASSERT_TRUE(shot.generate) << name;
        const Model a = prescore_shot(shot, nullptr), b = prescore_shot(shot, nullptr);
        EXPECT_EQ(a.settings_json, b.settings_json);
        EXPECT_NE(a.settings_json.find(std::string("\"kind\":\"") + name + "\""), std::string::npos) << a.settings_json;
        ASSERT_EQ(a.constraints.size(), b.constraints.size());
        for (size_t c = 0; c < a.constraints.size(); ++c) EXPECT_EQ(a.constraints[c].pivot, b.constraints[c].pivot);
    }
}

TEST(PaperScenes, TheBeamBreaksAtTheScoreAndGivesBackAlphaTimesItsStoredEnergy) {
    const Shot shot = asset("beam");
    const Model model = prescore_shot(shot, nullptr);
    double previous = -1;
    for (double alpha : {0.0, 0.5, 1.0, 1.5}) {
        const SimulationResult r = simulate(model, input_of(shot, alpha, 0.45), "beam");
        ASSERT_FALSE(r.breaks.empty()) << "alpha " << alpha;
        expect_books_balance(r, alpha);
        EXPECT_EQ(fragments(model, r), 2u);
        // The break comes from the block's slow push, the same in every run: the pieces are
        // nearly at rest, and what they move with right after is what the break gave back.
        const double t0 = r.breaks.front().time;
        EXPECT_LT(kinetic_at(r, t0 - 1.0 / 30), 0.01);
        const double after = kinetic_at(r, t0);
        EXPECT_GT(after, previous + 0.02) << "alpha " << alpha;
        previous = after;
    }
}

TEST(PaperScenes, TheChainBreaksOnceAtATimeAndItsEndsRecoilTowardTheirAnchors) {
    const Shot shot = asset("chain");
    ASSERT_GT(shot.simulate.rate_limit, 0);
    const Model model = prescore_shot(shot, nullptr);
    const uint32_t last = uint32_t(model.pieces.size() - 1);  // the end cubes are 0 and last
    double previous = -1;
    for (double alpha : {0.0, 0.5, 1.0, 2.0}) {
        const SimulationResult r = simulate(model, input_of(shot, alpha, 1.6), "chain");
        ASSERT_FALSE(r.breaks.empty()) << "alpha " << alpha;
        expect_books_balance(r, alpha);
        for (size_t i = 1; i < r.breaks.size(); ++i)
            EXPECT_GE(r.breaks[i].time - r.breaks[i - 1].time, shot.simulate.rate_limit - 1e-9);
        EXPECT_LT(r.breaks.size(), model.constraints.size() / 2) << "the chain broke everywhere";
        const double after = kinetic_at(r, r.breaks.front().time);
        EXPECT_GT(after, previous) << "alpha " << alpha;
        previous = after;
        // The two links at the break: each moves back toward the end cube it still hangs from.
        const BreakRecord& b = r.breaks.front();
        const uint32_t f0 = frame_at(r, b.time), f1 = frame_at(r, b.time + 0.3);
        for (auto [link, anchor] : {std::pair{b.piece_a, 0u}, std::pair{b.piece_b, last}}) {
            if (link == anchor) continue;
            const double d0 = (position(r, f0, link) - position(r, f0, anchor)).norm();
            const double d1 = (position(r, f1, link) - position(r, f1, anchor)).norm();
            EXPECT_LT(d1, d0) << "link " << link << " alpha " << alpha;
        }
    }
}

TEST(PaperScenes, ThePlateCracksOverTheSphereAndItsBooksBalance) {
    const Shot shot = asset("plate");
    const Model model = prescore_shot(shot, nullptr);
    ASSERT_EQ(model.pieces.size(), 25u);
    for (double alpha : {0.0, 1.5}) {
        const SimulationResult r = simulate(model, input_of(shot, alpha, 0.5), "plate");
        expect_books_balance(r, alpha);
        // It breaks where it lands on the sphere: the first breaks join the middle cube (12).
        EXPECT_TRUE(r.breaks.front().piece_a == 12 || r.breaks.front().piece_b == 12 ||
                    std::abs(r.breaks.front().pivot.x()) < 0.05);
    }
}

TEST(PaperScenes, TheBunnyDroppedOnTheSphereEndsInItsTenPieces) {
    const Shot shot = asset("bunny_sphere");
    const Model model = prescore_shot(shot, nullptr);
    ASSERT_EQ(model.pieces.size(), 10u);
    const double alpha = shot.material.alpha;
    const SimulationResult r = simulate(model, input_of(shot, alpha, 1.0), "bunny");
    expect_books_balance(r, alpha);
    EXPECT_EQ(fragments(model, r), 10u);
}

}  // namespace
}  // namespace shatter
