// [simulate] method (core/scene_settings.h, EnergizeMethod): the default "exact" and the paper's
// "paper" set energy_split, directions and exact_energy; keys beside the method and later layers
// override it; and on the bunny on the sphere (its breaks come on impact, the pieces moving) the
// default balances every break's books and conserves momentum, where the paper's magnitudes and
// directions do neither.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scenes/scene_support.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using namespace scenes_test;
using testing_support::TempDir;

Shot shot_of(TempDir& dir, const std::string& simulate, const std::vector<std::string>& overrides = {}) {
    return load_shot(dir.write("s.toml", "[generate]\nkind = \"beam\"\n[simulate]\n" + simulate), overrides);
}

TEST(EnergizeMethod, TheDefaultIsExactAndPaperSetsThePapersThreeKeys) {
    TempDir dir;
    const Shot d = shot_of(dir, "");
    EXPECT_EQ(d.simulate.method, EnergizeMethod::Exact);
    EXPECT_EQ(d.simulate.energy_split, EnergySplitMode::Total);
    EXPECT_EQ(d.simulate.directions, KickDirectionMode::Opposed);
    EXPECT_TRUE(d.simulate.exact_energy);
    const Shot p = shot_of(dir, "method = \"paper\"\n");
    EXPECT_EQ(p.simulate.method, EnergizeMethod::Paper);
    EXPECT_EQ(p.simulate.energy_split, EnergySplitMode::PerBody);
    EXPECT_EQ(p.simulate.directions, KickDirectionMode::Paper);
    EXPECT_FALSE(p.simulate.exact_energy);
    // A key beside the method overrides it, in either order in the file.
    const Shot k = shot_of(dir, "directions = \"force\"\nmethod = \"paper\"\n");
    EXPECT_EQ(k.simulate.directions, KickDirectionMode::Force);
    EXPECT_FALSE(k.simulate.exact_energy);
    // A method from --set replaces the file's keys; a key from --set beside it overrides it.
    const Shot s = shot_of(dir, "directions = \"force\"\n", {"simulate.method=paper"});
    EXPECT_EQ(s.simulate.directions, KickDirectionMode::Paper);
    const Shot t = shot_of(dir, "method = \"paper\"\n", {"simulate.exact_energy=true"});
    EXPECT_TRUE(t.simulate.exact_energy);
    EXPECT_EQ(t.simulate.directions, KickDirectionMode::Paper);
    // An unknown method names the key, the value and the valid ones.
    try {
        shot_of(dir, "method = \"fast\"\n");
        ADD_FAILURE() << "method = \"fast\" was accepted";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("simulate.method = \"fast\""), std::string::npos) << m;
        EXPECT_NE(m.find("\"exact\" or \"paper\""), std::string::npos) << m;
    }
}

// The bunny on the sphere breaks on impact, every piece moving: the books of the default hold on
// every break (injected = what the break releases in its frame: alpha E, with the energy held by
// earlier breaks it parts, or none while the joints hold its pieces; never negative), its kicks
// change no momentum (momentum work 0), and the paper's literal reading misses alpha E by more
// than 1%.
TEST(EnergizeMethod, OnImpactTheDefaultBalancesEveryBreakAndThePapersDoesNot) {
    const Shot shot = asset("bunny_sphere");
    ASSERT_EQ(shot.simulate.method, EnergizeMethod::Exact);
    const Model model = prescore_shot(shot, nullptr);
    SimulationInput in = input_of(shot, 1.0, 0.8);
    const SimulationResult exact = simulate(model, in, "bunny");
    ASSERT_GT(exact.breaks.size(), 100u);
    double stored = 0, injected = 0, held = 0;
    for (const BreakRecord& b : exact.breaks) {
        EXPECT_GE(b.injected_energy, 0);
        EXPECT_NEAR(b.injected_energy, given_back(b), 1e-9 + 1e-9 * (b.kicks.stored_energy + b.released_energy));
        EXPECT_NEAR(b.momentum_work, 0, 1e-9 * (b.kicks.stored_energy + b.released_energy) + 1e-15);
        stored += b.kicks.stored_energy, injected += b.injected_energy, held += b.held_energy - b.released_energy;
    }
    EXPECT_NEAR((injected + held) / stored, 1.0, 1e-9);
    apply_energize_method(EnergizeMethod::Paper, in.simulate);
    const SimulationResult paper = simulate(model, in, "bunny");
    double paper_stored = 0, paper_injected = 0;
    for (const BreakRecord& b : paper.breaks)
        paper_stored += b.kicks.stored_energy, paper_injected += b.injected_energy + b.momentum_work;
    EXPECT_GT(std::abs(paper_injected / paper_stored - 1.0), 0.01) << paper_injected << " J for " << paper_stored;
}

// A cantilever of three bars whose first bar is fixed breaks at its root under gravity: the two free
// bars sag as the joints stretch, so the joined group the kicks move has a velocity V, but its far
// end was joined to a body of infinite mass, which takes the kicks' momentum. Their energy is
// counted in the anchor's frame (the world's): the kinetic energy the kicks add in the world is
// what the break gives back, with no momentum work dP . V on top (counted in the group's own frame
// the kicks added 30 times alpha E).
TEST(EnergizeMethod, AKickNextToAnAnchorIsCountedInTheAnchorsFrame) {
    TempDir dir;
    const Shot shot = load_shot(dir.write("cantilever.toml", R"([generate]
kind = "beam"
count = 3
size = [0.1, 0.02, 0.02]
constraints_per_side = 2
density = 2500
[[object.driven]]
piece = 0
fixed = true
[scene]
ground = false
[material]
stiffness = 1e12
strength = 5e4
damping = 0
alpha = 1
[simulate]
fps = 120
substeps = 8
duration = 0.05
)"));
    ASSERT_EQ(shot.simulate.method, EnergizeMethod::Exact);
    const Model model = prescore_shot(shot, nullptr);
    const SimulationResult r = simulate(model, input_of(shot, 1.0, 0.05), "cantilever");
    ASSERT_GE(r.breaks.size(), 4u);
    int root_breaks = 0;
    for (const BreakRecord& b : r.breaks) {
        const double released = b.kicks.stored_energy + b.released_energy;
        EXPECT_GE(b.injected_energy, 0);
        EXPECT_NEAR(b.injected_energy, given_back(b), 1e-9 * released + 1e-15);
        EXPECT_NEAR(b.momentum_work, 0, 1e-9 * released + 1e-15) << "break at " << b.time << " s";
        if (b.piece_a == 0 || b.piece_b == 0) ++root_breaks;
    }
    EXPECT_GT(root_breaks, 0) << "no break at the anchored root";
}

}  // namespace
}  // namespace shatter
