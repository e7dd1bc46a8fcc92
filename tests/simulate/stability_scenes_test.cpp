// The stability map's 3D scenes (bench/study_stability_scenes.h, docs/accuracy.md section 6) with
// the default energized method (exact energy, opposed kicks, alpha 1) and direct joints: what
// each does at mass ratio 1,000, pinned. The study's table has every method and joint solve.
#include <gtest/gtest.h>

#include "bench/study_stability_scenes.h"

namespace shatter::study::scenes3d {
namespace {

Verdict default_direct(StudyCase c) {
    c.input.simulate.method = EnergizeMethod::Exact;
    apply_energize_method(EnergizeMethod::Exact, c.input.simulate);
    c.input.material.alpha = 1;
    c.input.simulate.joints = JointSolve::Direct;
    return run_and_judge(c);
}

// A 7.2 kg block (1,000 x a 7.2 g link) on six ball-jointed links hangs still, sagging
// sum_j W_j / k_j = ~0.5 mm over its 7 joints; the iterative solve (20 iterations) sags ~7 x that
// and opens its joints by over 1 mm (the study's table).
TEST(StabilityScenes, HeavyBlockOnALightChainHangsWhereItsSpringsSay) {
    const Verdict v = default_direct(hanging_case(1000));
    EXPECT_FALSE(v.guard_refuses);
    EXPECT_EQ(v.cls, Stability::Stable);
    EXPECT_EQ(v.breaks, 0u);
    EXPECT_LT(std::abs(v.measure), 0.01);  // sag / (m g / k_series) - 1 (measured 8e-5)
    EXPECT_LT(v.ke_end, 1e-3 * v.ke_peak);  // measured 1.9e-6 J of 0.0125 J
    EXPECT_TRUE(v.stable());
}

// A stack of four 5 cm boxes on the ground, each 10^(1/3) x heavier than the one below (top /
// bottom 10), stands still (top moved 0.11 mm after 1 s, no break)...
TEST(StabilityScenes, StackWithMassRatioTenStandsStill) {
    const Verdict v = default_direct(stack_case(10));
    EXPECT_EQ(v.cls, Stability::Stable);
    EXPECT_EQ(v.breaks, 0u);
    EXPECT_LT(v.measure, 1e-3);
    EXPECT_TRUE(v.stable());
}

// ...but at top / bottom 1,000 (masses 1 : 10 : 100 : 1,000; and at 100) it does not: the light
// bottom box is squeezed between the ground contact and a joint carrying 1,361 N, and every joint
// breaks within 0.15 s although each is 3 x stronger than its static load. With the bottom box
// fixed instead of on the ground it stands. A known failure, pinned so that a fix shows here.
TEST(StabilityScenes, StackWithMassRatioThousandCascadesEvenWithDirectJoints) {
    const Verdict v = default_direct(stack_case(1000));
    EXPECT_EQ(v.cls, Stability::Cascade);
    EXPECT_EQ(v.breaks, 12u);
    EXPECT_FALSE(v.stable());
}

// A welded tower of eight 4 cm glass cubes (10 MPa joints) hit at box 5 by a kinematic sphere at
// 10 m/s is knocked over as one body: no break, no joint opens 1 mm, no box faster than 2 x 10 m/s.
TEST(StabilityScenes, WeldedTowerHitByAFastSphereStaysWhole) {
    const Verdict v = default_direct(tower_case());
    EXPECT_EQ(v.cls, Stability::Stable);
    EXPECT_EQ(v.breaks, 0u);
    EXPECT_LT(v.open, 1e-3);
    EXPECT_LT(v.measure, 2 * kHitSpeed);
    EXPECT_TRUE(v.stable());
}

// At 1 MPa the same hit breaks joints, and not locally: in the contact's first step the direct
// solve loads the whole tower at once and 24 of its 28 constraints break, 16 of them far from
// the hit box (a cascade). Pinned as found.
TEST(StabilityScenes, WeakTowerHitByAFastSphereBreaksEverywhereAtOnce) {
    const Verdict v = default_direct(tower_case(1e6));
    EXPECT_EQ(v.cls, Stability::Cascade);
    EXPECT_GT(v.far_breaks, 8u);
    EXPECT_FALSE(v.stable());
}

}  // namespace
}  // namespace shatter::study::scenes3d
