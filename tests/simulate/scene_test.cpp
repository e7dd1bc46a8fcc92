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
