// A real material with the defaults (`shatter run MESH --set material.preset=P`): the default shot
// gives it the automatic step and direct joints (core/shot.h, default_shot_for_mesh), so that an
// impact's force is resolved and the joints break. At the fixed default step (1/480 s) the
// porcelain bunny's joints have omega h = 251 and an impact's peak force is resolved to about
// 1/251 of itself: nothing broke.
#include <gtest/gtest.h>

#include "scene_support.h"

namespace shatter {
namespace {

using namespace scenes_test;

TEST(RealMaterial, ThePorcelainBunnyDroppedWithTheDefaultsBreaks) {
    const Shot shot = default_shot_for_mesh("/usr/share/glmark2/models/bunny.obj", {"material.preset=porcelain"});
    ASSERT_TRUE(shot.simulate.auto_substeps);
    const Model model = prescore_shot(shot, nullptr);
    // The bunny lands at ~0.55 s; 0.4 s later the impact is over.
    const SimulationResult r = simulate(model, input_of(shot, 1.0, 0.95), "porcelain bunny");
    // Porcelain from 1.5 m is too gentle an impact to grade the seeds (damage number 0.0018):
    // uniform seeds. Measured: 44 of 241 joints into 3 fragments, 12.96 J stored (over the run).
    EXPECT_GT(r.breaks.size(), 20u);
    EXPECT_GE(fragments(model, r), 2u);
    // Every break gives back what it should: alpha E, in kinetic energy or held in a crack.
    for (const BreakRecord& b : r.breaks) {
        EXPECT_GE(b.injected_energy, -1e-12);
        EXPECT_NEAR(b.injected_energy + b.held_energy - b.released_energy, b.kicks.stored_energy,
                    1e-6 * b.kicks.stored_energy + 1e-12);
    }
}

}  // namespace
}  // namespace shatter
