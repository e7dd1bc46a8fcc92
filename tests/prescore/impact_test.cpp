// The impact pre-pass: first contacts of a rigid flight that are known in closed form (a tilted
// box's lowest corner on the ground, a box's face on a sphere's top, a projectile on a face), the
// contacts of several bodies, and no contact at all.
#include "prescore/impact.h"

#include <gtest/gtest.h>

#include <cmath>

#include "prescore/graded_seeds.h"
#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

constexpr double kG = 9.81;

// The surface of the box [0, s]^3 (model frame), as 12 triangles.
TriangleMesh box_surface(double s) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.vertices.push_back(Vec3(i & 1 ? s : 0, i & 2 ? s : 0, i & 4 ? s : 0));
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

SceneSettings ground_only() {
    SceneSettings scene;
    scene.gravity = Vec3(0, -kG, 0);
    return scene;
}

TEST(Impact, BoxDroppedTiltedTouchesTheGroundAtItsLowestCornerWhenFreeFallSays) {
    const double s = 0.1, tol = 1e-6;
    ObjectSettings object;
    object.pose.position = Vec3(0.2, 1.0, -0.1);
    object.pose.rotation_deg = Vec3(30, 10, 20);
    const Mat3 r = rotation_matrix(object.pose.rotation_deg);
    Vec3 lowest(0, 1e9, 0);
    for (const Vec3& v : box_surface(s).vertices)
        if (const Vec3 x = r * v + object.pose.position; x.y() < lowest.y()) lowest = x;
    const Impact impact = find_impact(box_surface(s), ground_only(), object, tol);
    ASSERT_EQ(impact.contacts.size(), 1u);
    const Contact& c = impact.contacts[0];
    EXPECT_EQ(c.with, "ground");
    const double t = std::sqrt(2 * lowest.y() / kG);
    EXPECT_NEAR(c.time, t, 1e-5);
    EXPECT_NEAR(c.point.x(), lowest.x(), 1e-9);
    EXPECT_NEAR(c.point.y(), 0, 2 * tol);
    EXPECT_NEAR(c.point.z(), lowest.z(), 1e-9);
    EXPECT_NEAR(c.speed, kG * t, 1e-3);
    EXPECT_NEAR(c.normal_speed, kG * t, 1e-3);
    // The corner in the model frame: (lowest - position) turned back.
    EXPECT_LT((c.model_point - r.transpose() * (lowest - object.pose.position)).norm(), 1e-9);
    ASSERT_EQ(impact.grading().size(), 1u);
}

TEST(Impact, FlatBoxOnAGroundTouchesAtTheCentreOfItsBottomFace) {
    ObjectSettings object;
    object.pose.position = Vec3(0, 0.5, 0);
    const Impact impact = find_impact(box_surface(0.1), ground_only(), object, 1e-6);
    ASSERT_EQ(impact.contacts.size(), 1u);
    EXPECT_LT((impact.contacts[0].model_point - Vec3(0.05, 0, 0.05)).norm(), 1e-9);
}

TEST(Impact, BoxDroppedOnASphereTouchesItsTopFirstAndTheGroundLater) {
    SceneSettings scene = ground_only();
    ColliderSettings ball;
    ball.name = "ball";
    ball.shape.kind = ShapeKind::Sphere;
    ball.shape.radius = 0.2;
    ball.pose.position = Vec3(0, 0.5, 0);
    scene.colliders.push_back(ball);
    ObjectSettings object;
    object.pose.position = Vec3(-0.07, 1.0, -0.03);  // the box's bottom face spans the sphere's top
    const Impact impact = find_impact(box_surface(0.1), scene, object, 1e-7);
    ASSERT_EQ(impact.contacts.size(), 2u);
    const Contact& c = impact.contacts[0];
    EXPECT_EQ(c.with, "ball");
    EXPECT_NEAR(c.time, std::sqrt(2 * (1.0 - 0.7) / kG), 1e-4);
    EXPECT_LT((c.point - Vec3(0, 0.7, 0)).norm(), 1e-3);
    EXPECT_LT((c.normal - Vec3::UnitY()).norm(), 1e-3);
    EXPECT_EQ(impact.contacts[1].with, "ground");  // the flight does not stop at the ball
    EXPECT_NEAR(impact.contacts[1].time, std::sqrt(2 * 1.0 / kG), 1e-5);
    ASSERT_EQ(impact.grading().size(), 1u);
    EXPECT_EQ(impact.grading()[0].with, "ball");
}

TEST(Impact, ProjectileFliesStraightAtTheFallingObjectAndHitsItsFace) {
    SceneSettings scene = ground_only();
    ProjectileSettings shot;
    shot.name = "shot";
    shot.shape.kind = ShapeKind::Sphere;
    shot.shape.radius = 0.02;
    shot.pose.position = Vec3(-1, 1.05, 0.05);
    shot.velocity = Vec3(10, 0, 0);
    scene.projectiles.push_back(shot);
    ObjectSettings object;
    object.pose.position = Vec3(0, 1, 0);
    const Impact impact = find_impact(box_surface(0.1), scene, object, 1e-7);
    ASSERT_EQ(impact.contacts.size(), 2u);
    const Contact& c = impact.contacts[0];
    EXPECT_EQ(c.with, "shot");
    const double t = 0.98 / 10;  // both fall alike: the gap closes at 10 m/s
    EXPECT_NEAR(c.time, t, 1e-6);
    EXPECT_LT((c.model_point - Vec3(0, 0.05, 0.05)).norm(), 1e-4);
    EXPECT_NEAR(c.point.y(), 1.05 - 0.5 * kG * t * t, 1e-4);
    EXPECT_NEAR(c.speed, 10, 1e-3);
    EXPECT_LT((c.normal - Vec3::UnitX()).norm(), 1e-3);
    EXPECT_EQ(impact.contacts[1].with, "ground");
}

TEST(Impact, NothingToHitFallsBackToUniformSeedsAndSaysSo) {
    SceneSettings scene = ground_only();
    scene.ground = false;
    ObjectSettings object;
    object.pose.position = Vec3(0, 1, 0);
    EXPECT_TRUE(find_impact(box_surface(0.1), scene, object, 1e-6).contacts.empty());

    const TetMesh mesh = test::cube_grid(4, 4, 4, 0.025);
    AutoChoices choices;
    PrescoreSettings settings;
    settings.seeds = SeedMode::Impact;
    const GradedSeeds g = grade_by_impact(mesh, build_topology(mesh), settings, scene, object, 0.17, choices);
    EXPECT_TRUE(g.density.empty());
    ASSERT_EQ(choices.list.size(), 1u);
    EXPECT_EQ(choices.list[0].what, "seeds uniform");
}

TEST(Impact, AnObjectRestingOnTheGroundIsNotAnImpact) {
    ObjectSettings object;  // at the origin: its bottom on the ground
    const Impact impact = find_impact(box_surface(0.1), ground_only(), object, 1e-6);
    ASSERT_EQ(impact.contacts.size(), 1u);
    EXPECT_EQ(impact.contacts[0].time, 0);
    EXPECT_TRUE(impact.grading().empty());
}

}  // namespace
}  // namespace shatter
