// Direct joints (simulate/bullet_solver.h, docs/physics.md section 5b) solve every joint row
// exactly whatever its constraint-force mixing, so a joint too soft for the iterative solve at
// the step (CFM above max_cfm, refused) is simulated, and hangs where its spring says.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

// Two 5 cm boxes of 2,400 kg/m^3 (0.3 kg each) stacked, joined by 2 x 2 constraints over their
// shared 5 x 5 cm face; the top one fixed, no ground. The bottom box hangs on the joints:
//   k_total = stiffness x face area = 1.728e6 N/m^3 x 0.0025 m^2 = 4,320 N/m,
//   omega = sqrt(k_total / m) = sqrt(4320 / 0.3) = 120 rad/s, omega h = 0.5 at h = 1/240 s,
// so CFM = 1 / (omega h)^2 = 4 (section 1): the iterative solve cannot converge, and refuses.
// Its rest stretch is m g / k_total = 0.3 x 9.81 / 4320 = 6.8125e-4 m.
constexpr double kStiffness = 1.728e6;
constexpr double kRestStretch = 0.3 * 9.81 / (kStiffness * 0.0025);

SimulationInput hanging(JointSolve joints) {
    SimulationInput in;
    in.scene.ground = false;
    in.material.stiffness = kStiffness;
    in.material.strength = 1e9;  // never breaks
    in.simulate.duration = 1;
    in.simulate.fps = 30;
    in.simulate.substeps = 8;
    in.simulate.joints = joints;
    return in;
}

TEST(DirectJoints, AJointTooSoftForTheIterativeSolveHangsWhereItsSpringSays) {
    const Model m = box_grid(1, 2, 1, 0.05, Vec3::Zero(), 2400, 2);
    ASSERT_EQ(m.pieces.size(), 2u);
    const uint32_t top = m.pieces[0].mass.center.y() > m.pieces[1].mass.center.y() ? 0 : 1;
    SimulationInput in = hanging(JointSolve::Iterative);
    in.object.driven.push_back({top, true, Vec3::Zero(), {}});
    EXPECT_THROW(simulate(m, in, "test"), Error);  // CFM 4 > max_cfm 0.5

    in.simulate.joints = JointSolve::Direct;
    const SimulationResult r = simulate(m, in, "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    const Trajectory& t = r.trajectory;
    const uint32_t bottom = 1 - top;
    // Implicit Euler damps the oscillation (|1 / (1 + i omega h)| = 0.89 a step): after 1 s the
    // box rests at its spring's stretch.
    const double drop = double(t.pose(0, bottom).position.y() - t.pose(t.frames() - 1, bottom).position.y());
    EXPECT_NEAR(drop, kRestStretch, 1e-3 * kRestStretch);
    EXPECT_EQ(r.breaks.size(), 0u);
}

}  // namespace
}  // namespace shatter
