// The scene around the object: scripted props push pieces, mesh colliders hold them, and the
// object starts where and how the shot places it.
#include <gtest/gtest.h>

#include <cmath>

#include "scenes/box_model.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

Model one_box(double side = 0.1) {
    BoxModelBuilder b;
    b.box(Vec3::Zero(), Vec3::Constant(side));
    return b.take();
}

TEST(Scene, AKinematicPropMovingAtConstantVelocityPushesAPiece) {
    SimulationInput in;
    KinematicSettings pusher;
    pusher.shape.size = Vec3(0.1, 0.1, 0.3);
    pusher.pose.position = Vec3(-0.3, 0.06, 0);
    pusher.velocity = Vec3(0.5, 0, 0);
    in.scene.kinematic.push_back(pusher);
    in.object.pose.position = Vec3(0, 0.05, 0);
    in.simulate.duration = 1.0;
    const SimulationResult r = simulate(one_box(), in, "test");
    const uint32_t last = r.trajectory.frames() - 1;
    EXPECT_EQ(r.trajectory.props, 1u);
    // The prop's face starts 0.2 m from the box's and moves 0.5 m: the box is pushed ~0.3 m.
    EXPECT_NEAR(r.trajectory.pose(last, 1).position.x(), -0.3f + 0.5f, 1e-5);
    EXPECT_GT(r.trajectory.pose(last, 0).position.x(), 0.25f);
}

// The books' constant (EnergySample): kinetic + potential + elastic + removed + what the joints,
// the contacts and the integration took, less what energizing and the drivers gave.
double books(const EnergySample& e) {
    return e.kinetic + e.potential + e.elastic + e.removed + e.joints_damped + e.contacts + e.integration -
           e.injected - e.driven;
}

// A steel ball of 2 cm (7,800 kg/m^3: 0.2614 kg) thrown at 2 m/s into a free 1 kg box, head on,
// no gravity, no restitution: they leave together at m v / (m + M) = 0.4145 m/s, momentum is
// kept, and the books count the ball's kinetic energy (0.5228 J at the start) and close.
TEST(Scene, AProjectileHitsAFreeBoxAndTheyLeaveWithItsMomentum) {
    SimulationInput in;
    in.scene.ground = false;
    in.scene.gravity = Vec3::Zero();
    ProjectileSettings ball;
    ball.shape.kind = ShapeKind::Sphere;
    ball.shape.radius = 0.02;
    ball.pose.position = Vec3(-0.3, 0, 0);
    ball.velocity = Vec3(2, 0, 0);
    ball.surface = {0.5, 0};
    in.scene.projectiles.push_back(ball);
    in.material.surface = SurfaceSettings{0.5, 0};
    in.simulate.duration = 0.5;
    const Model box = one_box();  // 10 cm of 1,000 kg/m^3
    const SimulationResult r = simulate(box, in, "test");
    const Trajectory& t = r.trajectory;
    ASSERT_EQ(t.props, 1u);
    const double m = projectile_mass(ball), M = box.pieces[0].mass.mass;
    EXPECT_NEAR(m, 7800 * 4.0 / 3.0 * M_PI * 0.02 * 0.02 * 0.02, 1e-12);
    EXPECT_NEAR(r.energy.front().kinetic, 0.5 * m * 4, 1e-9);
    const uint32_t f = t.frames() - 1;
    const auto speed = [&](uint32_t body) { return double(t.pose(f, body).position.x() - t.pose(f - 1, body).position.x()) * t.fps; };
    const double v_box = speed(0), v_ball = speed(1), v_common = m * 2 / (m + M);
    EXPECT_NEAR(m * v_ball + M * v_box, m * 2, 1e-4 * m * 2);  // momentum (float poses)
    EXPECT_NEAR(v_box, v_common, 0.02 * v_common);
    EXPECT_NEAR(v_ball, v_common, 0.02 * v_common);
    EXPECT_NEAR(r.energy.back().kinetic, 0.5 * (m + M) * v_common * v_common, 0.02 * 0.5 * m * 4);
    EXPECT_GT(r.energy.back().contacts, 0.3);  // the inelastic impact took most of it
    EXPECT_NEAR(books(r.energy.back()), books(r.energy.front()), 1e-9);
}

// Thrown under gravity it flies the parabola p0 + v t + g t^2 / 2 (semi-implicit Euler runs
// ahead by g h t / 2), and the books close over its flight.
TEST(Scene, AProjectileFliesItsParabola) {
    SimulationInput in;
    in.scene.ground = false;
    ProjectileSettings ball;
    ball.shape.kind = ShapeKind::Box;
    ball.shape.size = Vec3(0.02, 0.02, 0.02);
    ball.pose.position = Vec3(0, 5, 0);
    ball.velocity = Vec3(3, 4, 0);
    in.scene.projectiles.push_back(ball);
    in.object.pose.position = Vec3(0, -10, 0);
    in.simulate.duration = 1.0;
    const SimulationResult r = simulate(one_box(), in, "test");
    const Trajectory& t = r.trajectory;
    const double time = 1.0, h = 1.0 / (in.simulate.fps * in.simulate.substeps), g = 9.81;
    const Eigen::Vector3f p = t.pose(t.frames() - 1, 1).position;
    EXPECT_NEAR(p.x(), 3 * time, 1e-5);
    EXPECT_NEAR(p.y(), 5 + 4 * time - 0.5 * g * time * time, 0.5 * g * h * time * 1.01);
    EXPECT_NEAR(books(r.energy.back()), books(r.energy.front()), 1e-9);
}

TEST(Scene, AMeshColliderHoldsAPieceDroppedOnIt) {
    SimulationInput in;
    in.scene.ground = false;
    ColliderSettings table;
    table.shape.kind = ShapeKind::Mesh;
    table.shape.mesh = SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj";  // the unit cube [0, 1]^3
    in.scene.colliders.push_back(table);
    in.object.pose.position = Vec3(0.5, 1.3, 0.5);
    in.simulate.duration = 1.0;
    const SimulationResult r = simulate(one_box(), in, "test");
    const float y = r.trajectory.pose(r.trajectory.frames() - 1, 0).position.y();
    EXPECT_NEAR(y, 1.05f, 0.01f);  // resting on the cube's top face (the box is 10 cm)
}

TEST(Scene, PlaceBasePutsTheBottomOfTheRotatedBoundingBoxAtThePosition) {
    SimulationInput in;
    in.scene.ground = false;
    in.scene.gravity = Vec3::Zero();
    in.object.pose.position = Vec3(1, 2, 3);
    in.object.pose.rotation_deg = Vec3(0, 0, 45);  // the 10 cm box on an edge: 7.07 cm below its centre
    in.object.place = Placement::Base;
    in.simulate.duration = 0.1;
    const Model box = one_box();  // centred on the model frame's origin
    const SimulationResult r = simulate(box, in, "test");
    const Eigen::Vector3f centre = r.trajectory.pose(0, 0).position;
    EXPECT_NEAR(centre.x(), 1.0f, 1e-6);
    EXPECT_NEAR(centre.y(), 2.0f + 0.05f * std::sqrt(2.0f), 1e-6);
    EXPECT_NEAR(centre.z(), 3.0f, 1e-6);
}

TEST(Scene, TheObjectStartsWhereAndHowTheShotPlacesIt) {
    SimulationInput in;
    in.scene.ground = false;
    in.scene.gravity = Vec3::Zero();
    in.object.pose.position = Vec3(1, 2, 3);
    in.object.pose.rotation_deg = Vec3(0, 90, 0);
    in.object.velocity = Vec3(0.5, 0, 0);
    in.simulate.duration = 1.0;
    const SimulationResult r = simulate(one_box(), in, "test");
    const BodyPose& first = r.trajectory.pose(0, 0);
    const BodyPose& last = r.trajectory.pose(r.trajectory.frames() - 1, 0);
    EXPECT_LT((first.position - Eigen::Vector3f(1, 2, 3)).norm(), 1e-6);
    EXPECT_LT((last.position - Eigen::Vector3f(1.5, 2, 3)).norm(), 1e-5);
    // The model's x axis turned 90 degrees about y goes to -z.
    EXPECT_LT((first.rotation * Eigen::Vector3f::UnitX() - Eigen::Vector3f(0, 0, -1)).norm(), 1e-6);
}

}  // namespace
}  // namespace shatter
