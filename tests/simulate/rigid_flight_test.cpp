// Rigid flight (simulate/bullet_world.h, WorldSetup::rigid_flight): an object without spin that
// touches nothing falls as one body, its joints unsolved, until something comes within reach.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scenes/box_model.h"
#include "simulate/bullet_world.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

// 3 x 3 joined cubes of 2 cm (a plate 6 cm wide), its underside 0.3 m above the ground.
Model plate() { return box_grid(3, 1, 3, 0.02, Vec3(-0.03, 0, -0.03), 2400, 2); }

WorldSetup drop(double h) {
    WorldSetup setup;
    setup.object.pose.position = Vec3(0, 0.3, 0);
    setup.material.stiffness = 1e10;
    setup.material.strength = 1e9;  // never breaks
    setup.h = h;
    return setup;
}

// The lowest point of the pieces' hulls, from their poses.
double lowest(const BulletWorld& world, const Model& model) {
    double low = INFINITY;
    for (uint32_t i = 0; i < world.pieces(); ++i) {
        const Eigen::Quaterniond r = world.piece_pose(i).rotation.cast<double>();
        const Piece& piece = model.pieces[i];
        for (const Vec3& v : piece.collision.front().points)
            low = std::min(low, (r * (v - piece.mass.center) + world.piece_position(i)).y());
    }
    return low;
}

// The plate falls on the parabola, exactly at any step, with the velocities every-joint-solved
// would give it; the solver's own update (x += v h after v += g h) runs ahead of it by g h t / 2.
// The flight ends before it touches the ground, at the step whose fall would bring it within
// contact reach (a 2 cm cube's contact threshold is 0.35 mm, docs/physics.md section 6).
TEST(RigidFlight, FallsOnTheParabolaAndEndsJustBeforeTheGround) {
    const Model model = plate();
    const double h = 1.0 / 240;
    WorldSetup solved_setup = drop(h);
    solved_setup.rigid_flight = false;
    BulletWorld flying(model, drop(h)), solved(model, solved_setup);
    ASSERT_TRUE(flying.flying());
    ASSERT_FALSE(solved.flying());
    const double g = 9.81;
    std::vector<Vec3> start;
    for (uint32_t i = 0; i < model.pieces.size(); ++i) start.push_back(flying.piece_position(i));
    double gap = INFINITY, speed = 0;
    while (flying.flying()) {
        ASSERT_LT(flying.time(), 1.0);
        gap = lowest(flying, model);
        speed = std::abs(flying.piece_velocity(0).y());
        EXPECT_GT(gap, 0) << "at " << flying.time();
        flying.step();
        solved.step();
        if (!flying.flying()) break;  // that step was solved: it came within reach
        // The books: the fall is exact, so gravity's work is the potential energy it lost and the
        // integration books nothing.
        EXPECT_EQ(flying.step_work().integration, 0.0);
        const double t = flying.time();
        for (uint32_t i = 0; i < model.pieces.size(); ++i) {
            EXPECT_NEAR((flying.piece_position(i) - start[i] - Vec3(0, -g * t * t / 2, 0)).norm(), 0, 1e-9);
            EXPECT_NEAR((solved.piece_position(i) - flying.piece_position(i) - Vec3(0, -g * h * t / 2, 0)).norm(), 0, 1e-9);
            EXPECT_NEAR((flying.piece_velocity(i) - solved.piece_velocity(i)).norm(), 0, 1e-9);
        }
    }
    // The flight ended at the start of the step that began `gap` above the ground (not inside it:
    // checked above) and would have ended within contact reach of it (the thresholds, 0.35 mm each)
    // after one step's fall.
    const double fall = (speed + g * h / 2) * h;
    EXPECT_LT(gap - fall, 3 * 0.35e-3);
    // Free fall from 0.3 m: the flight ended within a step of the touch, sqrt(2 x 0.3 / g).
    EXPECT_NEAR(flying.flight_end(), std::sqrt(2 * 0.3 / g), h);
}

// Spin, or a driven piece, loads the joints: no flight.
TEST(RigidFlight, NotForASpinningObjectNorOneWithADrivenPiece) {
    const Model model = plate();
    WorldSetup spinning = drop(1.0 / 240);
    spinning.object.angular_velocity = Vec3(0, 1, 0);
    EXPECT_FALSE(BulletWorld(model, spinning).flying());
    WorldSetup driven = drop(1.0 / 240);
    driven.object.driven.push_back({0, true, Vec3::Zero(), {}});
    EXPECT_FALSE(BulletWorld(model, driven).flying());
    WorldSetup resting = drop(1.0 / 240);
    resting.object.pose.position = Vec3(0, 0, 0);  // on the ground
    EXPECT_FALSE(BulletWorld(model, resting).flying());
}

// A ball thrown at the object floating without gravity: the flight ends before the ball
// arrives, and the hit moves the object as a free body (momentum m v = (m + M) v' kept along x).
TEST(RigidFlight, AProjectileEndsTheFlightBeforeItArrives) {
    const Model model = plate();
    SimulationInput in;
    in.scene.ground = false;
    in.scene.gravity = Vec3::Zero();
    in.object.pose.position = Vec3(0, 0, 0);
    in.material.stiffness = 1e10;
    in.material.strength = 1e9;
    ProjectileSettings ball;
    ball.shape.kind = ShapeKind::Sphere;
    ball.shape.radius = 0.01;
    ball.pose.position = Vec3(-0.3, 0.01, 0);
    ball.velocity = Vec3(2, 0, 0);
    ball.surface = {0.5, 0};
    in.scene.projectiles.push_back(ball);
    in.material.surface = SurfaceSettings{0.5, 0};
    in.simulate.duration = 0.5;
    const SimulationResult flying = simulate(model, in, "test");
    in.simulate.rigid_flight = false;
    const SimulationResult solved = simulate(model, in, "test");
    const uint32_t last = flying.trajectory.frames() - 1;
    const uint32_t ball_body = flying.trajectory.pieces;
    // The plate's centre moved along x as much either way (momentum through the same contact).
    double x_flying = 0, x_solved = 0;
    for (uint32_t i = 0; i < model.pieces.size(); ++i) {
        x_flying += flying.trajectory.pose(last, i).position.x() / model.pieces.size();
        x_solved += solved.trajectory.pose(last, i).position.x() / model.pieces.size();
    }
    EXPECT_GT(x_flying, 0.01);
    EXPECT_NEAR(x_flying, x_solved, 1e-4);
    EXPECT_NEAR(flying.trajectory.pose(last, ball_body).position.x(), solved.trajectory.pose(last, ball_body).position.x(),
                1e-4);
}

}  // namespace
}  // namespace shatter
