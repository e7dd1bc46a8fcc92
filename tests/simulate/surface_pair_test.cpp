// A pair of surfaces in contact (simulate/surface_pair.h): friction the geometric mean of the
// two coefficients, restitution the larger of the two, as the simulation applies them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/trajectory.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"
#include "simulate/surface_pair.h"

namespace shatter {
namespace {

constexpr double kG = 9.81;

// One 10 cm cube (2,400 kg/m^3), its underside `height` above the ground, recorded at 240 fps.
SimulationInput cube_at(double height) {
    SimulationInput in;
    in.object.pose.position = Vec3(0, height, 0);
    in.simulate.fps = 240;
    in.simulate.substeps = 2;
    in.simulate.duration = 1.0;
    return in;
}

Model cube() { return box_grid(1, 1, 1, 0.1, Vec3(-0.05, 0, -0.05), 2400, 2); }

TEST(SurfacePair, AMaterialAgainstItselfKeepsItsOwnFigures) {
    EXPECT_DOUBLE_EQ(pair_friction(0.05, 0.05), 0.05);
    EXPECT_DOUBLE_EQ(pair_restitution(0.3, 0.3), 0.3);
    EXPECT_DOUBLE_EQ(pair_friction(0.2, 0.8), 0.4);
    EXPECT_DOUBLE_EQ(pair_restitution(0.1, 0.3), 0.3);
}

// Pushed at v0 = 1 m/s along the ground, the cube slides v0^2 / (2 mu g) before it stops. Cube
// 0.2 on ground 0.8: mu = 0.4, 0.1274 m (Bullet's product, 0.16, would give 0.3186 m). Bullet
// stops it 2% to 5% short at steps from 1/240 s to 1/3,840 s, not converging with the step
// (docs/log.md): within 4% at this one.
TEST(SurfacePair, ACubeSlidesAsFarAsThePairsFrictionLetsIt) {
    SimulationInput in = cube_at(1e-4);
    in.object.velocity = Vec3(1, 0, 0);
    in.material.surface = SurfaceSettings{0.2, 0};
    in.scene.ground_surface = SurfaceSettings{0.8, 0};
    const SimulationResult r = simulate(cube(), in, "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    const Trajectory& t = r.trajectory;
    const double slid = double(t.pose(t.frames() - 1, 0).position.x() - t.pose(0, 0).position.x());
    const double predicted = 1.0 / (2 * 0.4 * kG);
    EXPECT_NEAR(slid, predicted, 0.04 * predicted);
    // At rest at the end (it stops after v0 / (mu g) = 0.255 s).
    const double speed = double(t.pose(t.frames() - 1, 0).position.x() - t.pose(t.frames() - 2, 0).position.x()) * t.fps;
    EXPECT_LT(std::abs(speed), 1e-3);
}

// Dropped from 0.2 m, the cube meets the ground at sqrt(2 g 0.2) = 1.98 m/s. A pair bounces with
// the larger restitution of its two: the cube 0.5 on the ground 0, the cube 0 on the ground 0.5
// and both 0.5 make the same film (Bullet's product: no bounce, no bounce, 0.25), and it bounces.
// Not by the full e^2 x 0.2 m = 5 cm: Bullet's contact appears within its margin before the touch,
// and its target speed out of the ground is e v less the gap closed in the step (measured: 2.1 cm).
TEST(SurfacePair, ACubeBouncesWithTheLargerRestitution) {
    const auto drop = [](double cube_e, double ground_e) {
        SimulationInput in = cube_at(0.2);
        in.material.surface = SurfaceSettings{0.5, cube_e};
        in.scene.ground_surface = SurfaceSettings{0.5, ground_e};
        const SimulationResult r = simulate(cube(), in, "test");
        EXPECT_TRUE(r.complete) << r.stop_reason;
        return r.trajectory;
    };
    const Trajectory t = drop(0.5, 0);
    for (const Trajectory& other : {drop(0, 0.5), drop(0.5, 0.5)}) {
        ASSERT_EQ(other.poses.size(), t.poses.size());
        for (size_t i = 0; i < t.poses.size(); ++i) {
            EXPECT_EQ(other.poses[i].position, t.poses[i].position) << i;
            EXPECT_EQ(other.poses[i].rotation.coeffs(), t.poses[i].rotation.coeffs()) << i;
        }
    }
    // The centre's rise over its 5 cm on the ground: its highest frame over the 0.25 s after the
    // landing (the first frame after the fall time sqrt(2 x 0.2 / g) = 0.202 s).
    const auto rise = [](const Trajectory& traj) {
        const uint32_t landed = uint32_t(std::ceil(std::sqrt(2 * 0.2 / kG) * traj.fps)) + 1;
        double top = 0;
        for (uint32_t f = landed; f < std::min(traj.frames(), landed + uint32_t(0.25 * traj.fps)); ++f)
            top = std::max(top, double(traj.pose(f, 0).position.y()));
        return top - 0.05;
    };
    EXPECT_GT(rise(t), 0.01);          // it left the ground
    EXPECT_LT(rise(drop(0, 0)), 0.002);  // without restitution it stays
}

}  // namespace
}  // namespace shatter
