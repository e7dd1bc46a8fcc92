// The impact pre-pass: first contacts of a rigid flight that are known in closed form (a tilted
// box's lowest corner on the ground, a box's face on a sphere's top, a projectile on a face), the
// contacts of several bodies, and no contact at all.
#include "prescore/impact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

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
    const GradedSeeds g = grade_by_impact(mesh, build_topology(mesh), settings, scene, object, MaterialSettings{}, 0.17,
                                          choices);
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

// A slab given as a triangle mesh collider (1 x 0.05 x 1 m, its top at y = 0.3): the box's bottom
// face, 0.7 m above it, lands flat after sqrt(2 x 0.7 / g), at the face's centre, on +Y, closing
// at g t. The same slab as a box collider is touched at the same time.
TEST(Impact, BoxDroppedOnAMeshSlabTouchesWhenFreeFallSays) {
    SceneSettings scene = ground_only();
    ColliderSettings slab;
    slab.name = "slab";
    slab.shape.kind = ShapeKind::Mesh;
    slab.pose.position = Vec3(-0.5, 0.25, -0.5);
    scene.colliders.push_back(slab);
    TriangleMesh slab_mesh = box_surface(1);  // [0, 1]^3 squashed to 1 x 0.05 x 1
    for (Vec3& v : slab_mesh.vertices) v.y() *= 0.05;
    const std::vector<TriangleMesh> meshes = {slab_mesh};
    ObjectSettings object;
    object.pose.position = Vec3(0, 1.0, 0);
    const Impact impact = find_impact(box_surface(0.1), scene, object, 1e-6, &meshes);
    ASSERT_EQ(impact.contacts.size(), 2u);
    EXPECT_EQ(impact.mesh_colliders_skipped, 0u);
    const Contact& c = impact.contacts[0];
    EXPECT_EQ(c.with, "slab");
    const double t = std::sqrt(2 * 0.7 / kG);
    EXPECT_NEAR(c.time, t, 1e-9);
    EXPECT_LT((c.model_point - Vec3(0.05, 0, 0.05)).norm(), 1e-9);
    EXPECT_NEAR(c.point.y(), 0.3, 1e-9);
    EXPECT_LT((c.normal - Vec3::UnitY()).norm(), 1e-9);
    EXPECT_NEAR(c.speed, kG * t, 1e-9);
    EXPECT_NEAR(c.normal_speed, kG * t, 1e-9);
    EXPECT_EQ(impact.contacts[1].with, "ground");  // the slab does not hide the ground from the pre-pass
    // Without the meshes the collider is skipped and counted.
    EXPECT_EQ(find_impact(box_surface(0.1), scene, object, 1e-6).mesh_colliders_skipped, 1u);

    scene.colliders[0].shape.kind = ShapeKind::Box;
    scene.colliders[0].shape.size = Vec3(1, 0.05, 1);
    scene.colliders[0].pose.position = Vec3(0, 0.275, 0);
    EXPECT_NEAR(find_impact(box_surface(0.1), scene, object, 1e-6).contacts[0].time, t, 1e-5);
}

// A spike of the mesh (a tetrahedron whose apex points up at (0.05, 0.2, 0.05)) meets the falling
// box's bottom face inside it, not at a vertex of the box: it is found by the mesh's vertices
// crossing the object's triangles, at sqrt(2 x 0.8 / g), under the apex.
TEST(Impact, AMeshSpikeHitsTheInsideOfTheBoxsFace) {
    SceneSettings scene = ground_only();
    ColliderSettings spike;
    spike.shape.kind = ShapeKind::Mesh;
    scene.colliders.push_back(spike);
    TriangleMesh m;
    m.vertices = {Vec3(-0.5, 0, -0.5), Vec3(0.6, 0, -0.5), Vec3(0.05, 0, 0.6), Vec3(0.05, 0.2, 0.05)};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    const std::vector<TriangleMesh> meshes = {m};
    ObjectSettings object;
    object.pose.position = Vec3(0, 1.0, 0);
    const Impact impact = find_impact(box_surface(0.1), scene, object, 1e-6, &meshes);
    ASSERT_GE(impact.contacts.size(), 1u);
    const Contact& c = impact.contacts[0];
    EXPECT_EQ(c.with, "mesh");
    EXPECT_NEAR(c.time, std::sqrt(2 * 0.8 / kG), 1e-9);
    EXPECT_LT((c.model_point - Vec3(0.05, 0, 0.05)).norm(), 1e-9);
    EXPECT_LT((c.point - Vec3(0.05, 0.2, 0.05)).norm(), 1e-9);
    EXPECT_NEAR(c.normal.y(), 1, 1e-9);  // the box's face, turned to face the box
}

// impact_ratio and impact_radius "auto" (graded_seeds.h): D = rho v^2 / strength. The default
// shot's cast (1,100 kg/m^3, 20 kPa) hitting at sqrt(2 g 1.5) = 5.42 m/s: D = 1.62, ratio 1 + 12 D
// = 20.4, radius 0.2 (D / 1.6)^(1/5) = 0.2004 of the diagonal; both grow with the speed and fall
// with the strength, within their bounds.
TEST(GradedSeeds, AutoRatioAndRadiusFollowTheDamageNumber) {
    const double v = std::sqrt(2 * kG * 1.5), diagonal = 0.3;
    const AutoGrading a = auto_grading(1100, 2e4, v, diagonal);
    EXPECT_NEAR(a.damage, 1100 * 2 * kG * 1.5 / 2e4, 1e-12);
    EXPECT_NEAR(a.damage, 1.6187, 1e-4);
    EXPECT_NEAR(a.ratio, 20.42, 0.01);
    EXPECT_NEAR(a.radius / diagonal, 0.2 * std::pow(1.6187 / 1.6, 0.2), 1e-4);
    double last_ratio = 0, last_radius = 0;
    for (double drop : {0.05, 0.25, 0.5, 1.5, 5.0, 20.0}) {
        const AutoGrading b = auto_grading(1100, 2e4, std::sqrt(2 * kG * drop), diagonal);
        EXPECT_GE(b.ratio, last_ratio);
        EXPECT_GE(b.radius, last_radius);
        last_ratio = b.ratio, last_radius = b.radius;
    }
    EXPECT_EQ(auto_grading(1100, 2e4, 0, diagonal).ratio, 1);             // a touch grades nothing
    EXPECT_EQ(auto_grading(1100, 2e4, 100, diagonal).ratio, kMaxAutoRatio);  // D = 550: the cap
    EXPECT_NEAR(auto_grading(1100, 2e4, 100, diagonal).radius, 2 * kAutoRadius * diagonal, 1e-12);
    EXPECT_NEAR(auto_grading(1100, 2e4, 0.01, diagonal).radius, 0.5 * kAutoRadius * diagonal, 1e-12);
    // Glass (2,500 kg/m^3, 40 MPa): D = 0.0018, the drop hardly grades it.
    EXPECT_NEAR(auto_grading(2500, 4e7, v, diagonal).ratio, 1 + 12 * 2500 * 2 * kG * 1.5 / 4e7, 1e-12);
    EXPECT_LT(auto_grading(2500, 4e7, v, diagonal).ratio, 1.03);
}

// The grading of a cube of tets dropped 1.5 m on the ground takes the contact's own speed:
// the ratio is the formula's at sqrt(2 g h) (less the gap to the tolerance), and a number in the
// shot is used as given.
TEST(GradedSeeds, ADroppedCubeIsGradedByItsOwnImpactSpeed) {
    const TetMesh mesh = test::cube_grid(4, 4, 4, 0.025);
    ObjectSettings object;
    object.pose.position = Vec3(0, 1.5, 0);
    MaterialSettings material;
    material.strength = 2e4;
    PrescoreSettings settings;
    settings.seeds = SeedMode::Impact;
    settings.density = 1100;
    AutoChoices choices;
    const GradedSeeds g = grade_by_impact(mesh, build_topology(mesh), settings, ground_only(), object, material,
                                          0.17, choices);
    ASSERT_FALSE(g.density.empty());
    EXPECT_NEAR(g.damage, 1100 * 2 * kG * 1.5 / 2e4, 1e-3);
    EXPECT_NEAR(g.ratio, 1 + kRatioPerDamage * g.damage, 1e-9);
    EXPECT_TRUE(g.auto_ratio && g.auto_radius);
    settings.impact_ratio = 7;
    settings.impact_radius = Length{0.05, false};
    const GradedSeeds given = grade_by_impact(mesh, build_topology(mesh), settings, ground_only(), object, material,
                                              0.17, choices);
    EXPECT_EQ(given.ratio, 7);
    EXPECT_EQ(given.radius, 0.05);
    EXPECT_FALSE(given.auto_ratio || given.auto_radius);
}

// An impact too gentle to grade (graded_seeds.h, kMinAutoRatio): the automatic ratio 1 + 12 D is
// under 2 when D = rho v^2 / strength < 1 / 12, i.e. the cast (1,100 kg/m^3, 20 kPa) dropped less
// than h = strength / (12 rho 2 g) = 7.72 cm, and porcelain (2,400 kg/m^3, 40 MPa) from 1.5 m
// (D = 0.0018, ratio 1.02): uniform seeds, noted, the ratio it would have had recorded; a ratio
// given in the shot is used as it is.
TEST(GradedSeeds, AnImpactTooGentleToGradeGivesUniformSeedsAndSaysWhy) {
    const TetMesh mesh = test::cube_grid(4, 4, 4, 0.025);
    auto drop = [&](double height, double density, double strength, std::optional<double> ratio, AutoChoices& choices) {
        ObjectSettings object;
        object.pose.position = Vec3(0, height, 0);
        MaterialSettings material;
        material.strength = strength;
        material.density = density;
        PrescoreSettings settings;
        settings.seeds = SeedMode::Impact;
        settings.impact_ratio = ratio;
        return grade_by_impact(mesh, build_topology(mesh), settings, ground_only(), object, material, 0.17, choices);
    };
    const double threshold = 2e4 / (12 * 1100 * 2 * kG);
    EXPECT_NEAR(threshold, 0.0772, 1e-4);
    AutoChoices below, above, porcelain, given;
    const GradedSeeds low = drop(0.97 * threshold, 1100, 2e4, std::nullopt, below);
    EXPECT_TRUE(low.density.empty());
    EXPECT_NEAR(low.ratio, 1 + 12 * (0.97 / 12), 1e-6);  // D = 0.97 of the threshold's 1 / 12
    ASSERT_EQ(below.list.size(), 1u);
    EXPECT_EQ(below.list[0].what, "seeds uniform");
    EXPECT_NE(below.list[0].why.find("too gently to grade the seeds"), std::string::npos) << below.list[0].why;
    const nlohmann::ordered_json record = low.record();
    EXPECT_FALSE(record["graded"].get<bool>());
    EXPECT_NEAR(record["damage_number"].get<double>(), 0.97 / 12, 1e-3);

    EXPECT_FALSE(drop(1.03 * threshold, 1100, 2e4, std::nullopt, above).density.empty());

    const GradedSeeds p = drop(1.5, 2400, 4e7, std::nullopt, porcelain);
    EXPECT_TRUE(p.density.empty());
    EXPECT_NEAR(p.damage, 2400 * 2 * kG * 1.5 / 4e7, 1e-5);
    EXPECT_NEAR(p.ratio, 1.021, 1e-3);

    const GradedSeeds g = drop(1.5, 2400, 4e7, 1.5, given);
    EXPECT_FALSE(g.density.empty());
    EXPECT_EQ(g.ratio, 1.5);
}

}  // namespace
}  // namespace shatter
