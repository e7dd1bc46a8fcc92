// The shot file's [scene], [[scene.colliders]], [[scene.kinematic]], [object], [material] and
// [simulate] sections: every key read, every bad value refused with file:line, key, value and
// range; the scene settings' JSON round trip, by the tables of the arrays' entries too;
// rotations and kinematic motion against hand values.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/scene_settings.h"
#include "core/setting_table.h"
#include "core/shot.h"
#include "support/shot_error.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

std::string load_error(const std::string& path) { return testing_support::shot_load_error(path); }

// The error of a shot made of `text`; expects every one of `parts` in the message.
void expect_error(const std::string& text, std::initializer_list<const char*> parts) {
    TempDir dir;
    const std::string m = load_error(dir.write("s.toml", text));
    for (const char* p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
}

constexpr const char* kFullShot = R"([scene]
gravity = [0, -3.7, 0.5]
ground = false
ground_height = -0.25
ground_friction = 0.7
ground_restitution = 0.2

[[scene.colliders]]
name = "table"
shape = "box"
size = [2, 0.1, 1]
position = [0, 0.5, 0]
rotation = [0, 30, 0]
friction = 0.9
restitution = 0.05
colour = [0.5, 0.25, 0.125]

[[scene.colliders]]
name = "bowl"
shape = "mesh"
mesh = "props/bowl.obj"
mesh_scale = 0.01

[[scene.colliders]]
shape = "sphere"
radius = 0.3

[[scene.colliders]]
shape = "plane"
rotation = [0, 0, 90]

[[scene.kinematic]]
name = "hammer"
shape = "sphere"
radius = 0.05
position = [1, 1, 0]
velocity = [-2, 0, 0]
friction = 0.3
restitution = 0.4
colour = [1, 0, 0]

[[scene.kinematic]]
name = "press"
shape = "box"
size = [0.5, 0.1, 0.5]
rotation = [10, 0, 0]
keys = [[0, 0, 2, 0], [1.5, 0, 1, 0], [2, 0, 0.9, 0]]

[object]
position = [0, 1, 0]
rotation = [90, 0, 0]
velocity = [0, -1, 0]
angular_velocity = [0, 3, 0]

[material]
density = 2500
stiffness = 2e9
damping = 100
strength = 5e5
alpha = 0.5
friction = 0.6
restitution = 0.3

[simulate]
duration = 2.5
fps = 60
substeps = 4
iterations = 30
energy_split = "per_body"
directions = "opposed"
rate_limit = 0.01
rollback = true
exact_energy = true
seed = 7
max_cfm = 0.25
)";

TEST(SceneShot, ReadsEveryKeyOfSceneAndColliders) {
    TempDir dir;
    Shot s = load_shot(dir.write("shot.toml", kFullShot));
    EXPECT_EQ(s.scene.gravity, Vec3(0, -3.7, 0.5));
    EXPECT_FALSE(s.scene.ground);
    EXPECT_EQ(s.scene.ground_height, -0.25);
    EXPECT_EQ(s.scene.ground_surface.friction, 0.7);
    EXPECT_EQ(s.scene.ground_surface.restitution, 0.2);
    ASSERT_EQ(s.scene.colliders.size(), 4u);
    const ColliderSettings& table = s.scene.colliders[0];
    EXPECT_EQ(table.name, "table");
    EXPECT_EQ(table.shape.kind, ShapeKind::Box);
    EXPECT_EQ(table.shape.size, Vec3(2, 0.1, 1));
    EXPECT_EQ(table.pose.position, Vec3(0, 0.5, 0));
    EXPECT_EQ(table.pose.rotation_deg, Vec3(0, 30, 0));
    EXPECT_EQ(table.surface.friction, 0.9);
    EXPECT_EQ(table.surface.restitution, 0.05);
    EXPECT_EQ(table.colour, (std::array<float, 3>{0.5f, 0.25f, 0.125f}));
    EXPECT_EQ(s.scene.colliders[1].shape.kind, ShapeKind::Mesh);
    EXPECT_EQ(s.scene.colliders[1].shape.mesh, dir.file("props/bowl.obj"));  // beside the shot
    EXPECT_EQ(s.scene.colliders[1].shape.mesh_scale, 0.01);
    EXPECT_EQ(s.scene.colliders[2].shape.kind, ShapeKind::Sphere);
    EXPECT_EQ(s.scene.colliders[2].shape.radius, 0.3);
    EXPECT_EQ(s.scene.colliders[3].shape.kind, ShapeKind::Plane);
    EXPECT_EQ(s.scene.colliders[3].pose.rotation_deg, Vec3(0, 0, 90));
}

TEST(SceneShot, ReadsEveryKeyOfKinematicBodies) {
    TempDir dir;
    Shot s = load_shot(dir.write("shot.toml", kFullShot));
    ASSERT_EQ(s.scene.kinematic.size(), 2u);
    const KinematicSettings& hammer = s.scene.kinematic[0];
    EXPECT_EQ(hammer.name, "hammer");
    EXPECT_EQ(hammer.shape.kind, ShapeKind::Sphere);
    EXPECT_EQ(hammer.shape.radius, 0.05);
    EXPECT_EQ(hammer.pose.position, Vec3(1, 1, 0));
    EXPECT_EQ(hammer.velocity, Vec3(-2, 0, 0));
    EXPECT_TRUE(hammer.keys.empty());
    EXPECT_EQ(hammer.surface.friction, 0.3);
    EXPECT_EQ(hammer.surface.restitution, 0.4);
    EXPECT_EQ(hammer.colour, (std::array<float, 3>{1, 0, 0}));
    const KinematicSettings& press = s.scene.kinematic[1];
    EXPECT_EQ(press.shape.size, Vec3(0.5, 0.1, 0.5));
    EXPECT_EQ(press.pose.rotation_deg, Vec3(10, 0, 0));
    ASSERT_EQ(press.keys.size(), 3u);
    EXPECT_EQ(press.keys[1].time, 1.5);
    EXPECT_EQ(press.keys[2].position, Vec3(0, 0.9, 0));
    EXPECT_EQ(press.pose.position, Vec3(0, 2, 0));  // the pose at t = 0 is the first key
}

// A projectile's keys, its mass from its shape and density (a steel sphere of 3 cm: 0.8822 kg), and
// its place among the props: after the kinematic bodies.
TEST(SceneShot, ReadsEveryKeyOfAProjectile) {
    TempDir dir;
    const Shot s = load_shot(dir.write("shot.toml", std::string(kFullShot) + R"(
[[scene.projectile]]
name = "ball"
shape = "sphere"
radius = 0.03
position = [0, 0.5, -2]
rotation = [0, 0, 10]
velocity = [0, 1, 10]
density = 7800
friction = 0.2
restitution = 0.3
colour = [0.5, 0.5, 0.5]
)"));
    ASSERT_EQ(s.scene.projectiles.size(), 1u);
    const ProjectileSettings& ball = s.scene.projectiles[0];
    EXPECT_EQ(ball.name, "ball");
    EXPECT_EQ(ball.shape.kind, ShapeKind::Sphere);
    EXPECT_EQ(ball.pose.position, Vec3(0, 0.5, -2));
    EXPECT_EQ(ball.pose.rotation_deg, Vec3(0, 0, 10));
    EXPECT_EQ(ball.velocity, Vec3(0, 1, 10));
    EXPECT_EQ(ball.surface.friction, 0.2);
    EXPECT_EQ(ball.surface.restitution, 0.3);
    EXPECT_EQ(ball.colour, (std::array<float, 3>{0.5f, 0.5f, 0.5f}));
    EXPECT_NEAR(projectile_mass(ball), 7800 * 4.0 / 3.0 * M_PI * 0.03 * 0.03 * 0.03, 1e-12);
    const std::vector<KinematicSettings> props = scene_props(s.scene);
    ASSERT_EQ(props.size(), 3u);
    EXPECT_EQ(props[2].name, "ball");
    EXPECT_EQ(props[2].shape.radius, 0.03);
    // A box has a size, not a radius; keys are a kinematic body's.
    expect_error("[[scene.projectile]]\nshape = \"box\"\nradius = 0.1\n", {"s.toml:3", "scene.projectile[0].radius"});
    expect_error("[[scene.projectile]]\nkeys = [[0, 1, 1, 1]]\n", {"s.toml:2", "scene.projectile[0].keys"});
    expect_error("[[scene.projectile]]\ndensity = 0\n", {"s.toml:2", "scene.projectile[0].density"});
}

TEST(SceneShot, ReadsEveryKeyOfObjectMaterialAndSimulate) {
    TempDir dir;
    Shot s = load_shot(dir.write("shot.toml", kFullShot));
    EXPECT_EQ(s.object.pose.position, Vec3(0, 1, 0));
    EXPECT_EQ(s.object.pose.rotation_deg, Vec3(90, 0, 0));
    EXPECT_EQ(s.object.velocity, Vec3(0, -1, 0));
    EXPECT_EQ(s.object.angular_velocity, Vec3(0, 3, 0));
    EXPECT_EQ(s.material.density, 2500);
    EXPECT_EQ(s.material.stiffness, 2e9);
    EXPECT_EQ(s.material.damping, 100);
    EXPECT_EQ(s.material.strength, 5e5);
    EXPECT_EQ(s.material.alpha, 0.5);
    EXPECT_EQ(s.material.surface.friction, 0.6);
    EXPECT_EQ(s.material.surface.restitution, 0.3);
    EXPECT_EQ(s.simulate.duration, 2.5);
    EXPECT_EQ(s.simulate.fps, 60);
    EXPECT_EQ(s.simulate.substeps, 4u);
    EXPECT_EQ(s.simulate.iterations, 30u);
    EXPECT_EQ(s.simulate.energy_split, EnergySplitMode::PerBody);
    EXPECT_EQ(s.simulate.directions, KickDirectionMode::Opposed);
    EXPECT_EQ(s.simulate.rate_limit, 0.01);
    EXPECT_TRUE(s.simulate.rollback);
    EXPECT_TRUE(s.simulate.exact_energy);
    EXPECT_EQ(s.simulate.seed, 7u);
    EXPECT_EQ(s.simulate.max_cfm, 0.25);
}

TEST(SceneShot, AbsentSectionsKeepTheDocumentedDefaults) {
    TempDir dir;
    Shot s = load_shot(dir.write("shot.toml", "[material]\nalpha = 2\n"));
    EXPECT_EQ(s.scene.gravity, Vec3(0, -9.81, 0));
    EXPECT_TRUE(s.scene.ground);
    EXPECT_TRUE(s.scene.colliders.empty());
    EXPECT_FALSE(s.material.density.has_value());
    EXPECT_EQ(s.material.stiffness, 1e10);
    EXPECT_EQ(s.simulate.fps, 30);
    EXPECT_EQ(s.simulate.energy_split, EnergySplitMode::Total);
}

TEST(SceneShot, UnknownKeyInAColliderEntryNamesFileLineAndTheEntry) {
    TempDir dir;
    const std::string path =
        dir.write("s.toml", "[[scene.colliders]]\nshape = \"sphere\"\n\n"
                            "[[scene.colliders]]\nshape = \"box\"\nfrction = 1\n");
    const std::string m = load_error(path);
    EXPECT_NE(m.find(path + ":6"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown key 'scene.colliders[1].frction'"), std::string::npos) << m;
    EXPECT_NE(m.find("did you mean 'friction'"), std::string::npos) << m;
}

TEST(SceneShot, UnknownKeyInSceneObjectMaterialSimulateIsAnError) {
    expect_error("[scene]\ngravty = [0, -1, 0]\n", {"s.toml:2", "scene.gravty", "did you mean 'gravity'"});
    expect_error("[object]\nvelocty = [0, 0, 0]\n", {"s.toml:2", "object.velocty", "did you mean 'velocity'"});
    expect_error("[material]\nstrenght = 1\n", {"s.toml:2", "material.strenght", "did you mean 'strength'"});
    expect_error("[simulate]\nsubstep = 2\n", {"s.toml:2", "simulate.substep", "did you mean 'substeps'"});
    expect_error("[[scene.kinematic]]\nkeys = [[0, 1, 1, 1]]\nmesh = \"a.obj\"\n",
                 {"s.toml:3", "scene.kinematic[0].mesh"});
}

TEST(SceneShot, OutOfRangeValuesNameFileLineKeyValueAndRange) {
    expect_error("[scene]\ngravity = [0, -1e9, 0]\n",
                 {"s.toml:2", "scene.gravity[1] = -1e+09 is outside [-1000, 1000] m/s^2", "fix:"});
    expect_error("[material]\n\nalpha = -1\n", {"s.toml:3", "material.alpha = -1 is outside [0, 100]"});
    expect_error("[simulate]\nfps = 0\n", {"s.toml:2", "simulate.fps = 0 is outside [1, 1000] frames/s"});
    expect_error("[simulate]\nsubsteps = 0\n", {"simulate.substeps = 0 is outside [1, 10000]"});
    expect_error("[simulate]\nmax_cfm = 1\n", {"simulate.max_cfm = 1 is outside [1e-06, 0.99]"});
    expect_error("[[scene.colliders]]\nshape = \"sphere\"\nradius = 0\n",
                 {"s.toml:3", "scene.colliders[0].radius = 0 is outside [1e-06, 1e+06] m"});
    expect_error("[[scene.colliders]]\nsize = [1, -1, 1]\n", {"scene.colliders[0].size[1] = -1 is outside"});
    expect_error("[[scene.colliders]]\ncolour = [0.5, 2, 0]\n", {"scene.colliders[0].colour[1] = 2 is outside [0, 1]"});
    expect_error("[scene]\nground_restitution = 1.5\n", {"scene.ground_restitution = 1.5 is outside [0, 1]"});
    expect_error("[object]\nangular_velocity = [0, nan, 0]\n",
                 {"object.angular_velocity[1] = nan is not a finite number"});
    expect_error("[material]\ndensity = 0\n", {"material.density = 0 is outside [0.001, 100000] kg/m^3"});
}

TEST(SceneShot, WrongTypesAreRefusedWithAnExample) {
    expect_error("[scene]\ngravity = 9.81\n",
                 {"s.toml:2", "scene.gravity must be an array of 3 numbers", "write e.g. gravity = [0, -9.81, 0]"});
    expect_error("[scene]\ngravity = [0, -9.81]\n", {"scene.gravity must be an array of 3 numbers"});
    expect_error("[object]\nposition = [0, \"up\", 0]\n", {"s.toml:2", "object.position[1] is not a number"});
    expect_error("[scene]\nground = 1\n", {"scene.ground must be true or false"});
    expect_error("[simulate]\nsubsteps = 2.5\n", {"simulate.substeps must be a whole number"});
    expect_error("[simulate]\nrollback = \"yes\"\n", {"simulate.rollback must be true or false"});
    expect_error("[simulate]\nenergy_split = \"both\"\n",
                 {"s.toml:2", "simulate.energy_split = \"both\" is not one of \"total\", \"per_body\""});
    expect_error("[simulate]\ndirections = 1\n", {"simulate.directions must be a string"});
    expect_error("[scene]\ncolliders = 3\n",
                 {"scene.colliders must be an array of tables, each written [[scene.colliders]]"});
    expect_error("[[scene.colliders]]\nshape = \"cone\"\n",
                 {"scene.colliders[0].shape = \"cone\" is not one of \"box\", \"sphere\", \"plane\", \"mesh\""});
    expect_error("[[scene.kinematic]]\nkeys = [[0, 1, 2]]\n",
                 {"scene.kinematic[0].keys[0] must be an array of 4 numbers"});
    expect_error("[[scene.kinematic]]\nkeys = []\n", {"scene.kinematic[0].keys must be a non-empty array"});
}

TEST(SceneShot, KinematicKeysMustHaveStrictlyIncreasingTimes) {
    expect_error("[[scene.kinematic]]\nkeys = [[0, 0, 1, 0],\n        [1, 0, 2, 0],\n        [1, 0, 3, 0]]\n",
                 {"s.toml:4", "scene.kinematic[0].keys[2] has time 1 s, not after the key before it (1 s)",
                  "increasing time"});
    expect_error("[[scene.kinematic]]\nkeys = [[2, 0, 1, 0], [1, 0, 2, 0]]\n", {"keys[1] has time 1 s"});
    expect_error("[[scene.kinematic]]\nkeys = [[-1, 0, 1, 0]]\n",
                 {"scene.kinematic[0].keys[0][0] = -1 is outside [0, 3600] s"});
}

TEST(SceneShot, KinematicVelocityAndKeysTogetherAreRefused) {
    expect_error("[[scene.kinematic]]\nvelocity = [1, 0, 0]\nkeys = [[0, 0, 1, 0]]\n",
                 {"s.toml:3", "scene.kinematic[0].keys and scene.kinematic[0].velocity are both given", "keep one"});
    expect_error("[[scene.kinematic]]\nposition = [1, 0, 0]\nkeys = [[0, 0, 1, 0]]\n",
                 {"scene.kinematic[0].keys and scene.kinematic[0].position are both given"});
}

TEST(SceneShot, KinematicShapeMustBeBoxOrSphere) {
    expect_error("[[scene.kinematic]]\nshape = \"plane\"\n",
                 {"s.toml:2", "scene.kinematic[0].shape = \"plane\" is not one of \"box\", \"sphere\""});
}

TEST(SceneShot, KeyOfAnotherShapeAndMeshWithoutFileAreRefused) {
    expect_error("[[scene.colliders]]\nshape = \"box\"\nradius = 1\n",
                 {"s.toml:3", "scene.colliders[0].radius does not apply to shape = \"box\""});
    expect_error("[[scene.colliders]]\nradius = 1\n", {"radius does not apply to shape = \"box\""});
    expect_error("[[scene.colliders]]\nshape = \"plane\"\nsize = [1, 1, 1]\n",
                 {"size does not apply to shape = \"plane\""});
    expect_error("[[scene.colliders]]\nshape = \"sphere\"\nmesh = \"a.obj\"\n", {"mesh does not apply"});
    expect_error("[[scene.colliders]]\nshape = \"mesh\"\n",
                 {"s.toml:2", "scene.colliders[0].shape = \"mesh\" needs a mesh file"});
}

TEST(SceneShot, TheExampleInDocsShotMdLoads) {
    const std::string doc = read_file(SHATTER_SOURCE_DIR "/docs/shot.md");
    const size_t begin = doc.rfind("```toml\n");
    ASSERT_NE(begin, std::string::npos);
    const size_t end = doc.find("```", begin + 8);
    TempDir dir;
    Shot s = load_shot(dir.write("example.toml", doc.substr(begin + 8, end - begin - 8)));
    EXPECT_EQ(s.scene.colliders.size(), 1u);
    ASSERT_EQ(s.scene.kinematic.size(), 2u);
    EXPECT_EQ(kinematic_position(s.scene.kinematic[1], 0.25), Vec3(0, 0.75, 0));
    ASSERT_EQ(s.scene.projectiles.size(), 1u);
    EXPECT_EQ(s.scene.projectiles[0].velocity, Vec3(-6, 1, 0));
}

TEST(SceneShot, AbsoluteColliderMeshPathIsKept) {
    TempDir dir;
    Shot s = load_shot(dir.write("s.toml", "[[scene.colliders]]\nshape = \"mesh\"\nmesh = \"/data/bowl.obj\"\n"));
    EXPECT_EQ(s.scene.colliders[0].shape.mesh, "/data/bowl.obj");
}

// ---- rotation, kinematic motion, JSON -------------------------------------------------------

TEST(SceneSettings, RotationMatrixAppliesXThenYThenZ) {
    const double tol = 1e-12;
    EXPECT_LT((rotation_matrix(Vec3(90, 0, 0)) * Vec3::UnitY() - Vec3::UnitZ()).norm(), tol);
    EXPECT_LT((rotation_matrix(Vec3(0, 90, 0)) * Vec3::UnitZ() - Vec3::UnitX()).norm(), tol);
    EXPECT_LT((rotation_matrix(Vec3(0, 0, 90)) * Vec3::UnitX() - Vec3::UnitY()).norm(), tol);
    // X first takes Y to Z, which Z then leaves alone (the other order would give -X).
    EXPECT_LT((rotation_matrix(Vec3(90, 0, 90)) * Vec3::UnitY() - Vec3::UnitZ()).norm(), tol);
    // X takes Y to Z, then Y takes Z to X.
    EXPECT_LT((rotation_matrix(Vec3(90, 90, 0)) * Vec3::UnitY() - Vec3::UnitX()).norm(), tol);
    EXPECT_LT((rotation_matrix(Vec3::Zero()) - Mat3::Identity()).norm(), tol);
    const Mat3 r = rotation_matrix(Vec3(12, -34, 56));
    EXPECT_LT((r * r.transpose() - Mat3::Identity()).norm(), tol);
    EXPECT_NEAR(r.determinant(), 1.0, tol);
}

TEST(SceneSettings, KinematicWithoutKeysMovesAtConstantVelocity) {
    KinematicSettings k;
    k.pose.position = Vec3(1, 2, 3);
    k.velocity = Vec3(1, 0, -2);
    EXPECT_EQ(kinematic_position(k, 0), Vec3(1, 2, 3));
    EXPECT_EQ(kinematic_position(k, 0.5), Vec3(1.5, 2, 2));
}

TEST(SceneSettings, KinematicKeysInterpolateLinearlyAndHoldOutside) {
    KinematicSettings k;
    k.velocity = Vec3(100, 0, 0);  // ignored when there are keys
    k.keys = {{1, Vec3(0, 0, 0)}, {3, Vec3(2, 4, 0)}, {4, Vec3(2, 4, 10)}};
    EXPECT_EQ(kinematic_position(k, 0), Vec3(0, 0, 0));  // held before the first key
    EXPECT_EQ(kinematic_position(k, 1), Vec3(0, 0, 0));
    EXPECT_EQ(kinematic_position(k, 2), Vec3(1, 2, 0));
    EXPECT_EQ(kinematic_position(k, 3.5), Vec3(2, 4, 5));
    EXPECT_EQ(kinematic_position(k, 9), Vec3(2, 4, 10));  // held after the last
    std::swap(k.keys[0], k.keys[2]);                       // sorted by time before use
    EXPECT_EQ(kinematic_position(k, 2), Vec3(1, 2, 0));
}

SceneSettings busy_scene() {
    SceneSettings s;
    s.gravity = Vec3(0.1, -3.7, 0);
    s.ground = false;
    s.ground_height = -0.3;
    s.ground_surface = {0.7, 0.2};
    ColliderSettings box;
    box.name = "table";
    box.shape.size = Vec3(2, 0.1, 1.0 / 3);
    box.pose = {Vec3(0, 0.5, 0), Vec3(0, 30, 0)};
    box.colour = {0.1f, 0.2f, 0.3f};
    ColliderSettings mesh;
    mesh.shape.kind = ShapeKind::Mesh;
    mesh.shape.mesh = "props/bowl.obj";
    mesh.shape.mesh_scale = 0.01;
    ColliderSettings plane;
    plane.shape.kind = ShapeKind::Plane;
    s.colliders = {box, mesh, plane};
    KinematicSettings hammer;
    hammer.name = "hammer";
    hammer.shape.kind = ShapeKind::Sphere;
    hammer.shape.radius = 0.05;
    hammer.velocity = Vec3(-2, 0, 0);
    KinematicSettings press;
    press.keys = {{0, Vec3(0, 2, 0)}, {1.5, Vec3(0, 1, 0.1)}};
    press.surface = {0.25, 0.75};
    s.kinematic = {hammer, press};
    return s;
}

TEST(SceneSettings, SceneJsonRoundTripsExactly) {
    const SceneSettings s = busy_scene();
    const std::string text = to_json(s).dump();
    const SceneSettings back = scene_from_json(nlohmann::json::parse(text), "t.traj");
    EXPECT_EQ(to_json(back).dump(), text);
    EXPECT_EQ(back.colliders[0].shape.size, s.colliders[0].shape.size);
    EXPECT_EQ(back.colliders[0].colour, s.colliders[0].colour);
    EXPECT_EQ(back.colliders[1].shape.kind, ShapeKind::Mesh);
    EXPECT_EQ(back.kinematic[1].keys[1].position, Vec3(0, 1, 0.1));
    EXPECT_EQ(back.kinematic[1].surface.restitution, 0.75);
    EXPECT_NE(text.find("\"shape\":\"plane\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"colour\":[0.1,0.2,0.3]"), std::string::npos) << text;
}

// The message of scene_from_json on `j`.
std::string scene_json_error(const nlohmann::json& j) {
    try {
        scene_from_json(j, "t.traj");
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        return e.what();
    }
    return "no error";
}

TEST(SceneSettings, MalformedSceneJsonIsRefusedNamingTheSourceAndTheField) {
    auto error = scene_json_error;
    nlohmann::json good = nlohmann::json::parse(to_json(busy_scene()).dump());
    nlohmann::json j = good;
    j.erase("gravity");
    EXPECT_NE(error(j).find("t.traj: settings JSON: scene.gravity is missing"), std::string::npos) << error(j);
    j = good;
    j["colliders"][1]["shape"] = "cone";
    EXPECT_NE(error(j).find("scene.colliders[1].shape = \"cone\""), std::string::npos) << error(j);
    j = good;
    j["kinematic"][0]["extra"] = 1;
    EXPECT_NE(error(j).find("scene.kinematic[0].extra is not a known setting"), std::string::npos) << error(j);
    j = good;
    j["kinematic"][1]["keys"][1][0] = 0;
    EXPECT_NE(error(j).find("scene.kinematic[1].keys[1] has a time not after"), std::string::npos) << error(j);
    j = good;
    j["kinematic"][0]["shape"] = "plane";
    EXPECT_NE(error(j).find("box or sphere"), std::string::npos) << error(j);
    EXPECT_NE(error(nlohmann::json::array()).find("scene is not a JSON object"), std::string::npos);
}

template <class Root>
std::vector<std::string> table_keys(const std::vector<BasicSetting<Root>>& table) {
    std::vector<std::string> keys;
    for (const BasicSetting<Root>& s : table) keys.push_back(s.key);
    return keys;
}

std::vector<std::string> json_keys(const nlohmann::ordered_json& j) {
    std::vector<std::string> keys;
    for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
    return keys;
}

// The table of an entry is its one declaration: the entry's JSON has the table's keys in table
// order, and reading it back needs every one of them.
TEST(SceneSettings, ArrayEntriesWriteAndReadBackTheKeysOfTheirTables) {
    const nlohmann::ordered_json scene = to_json(busy_scene());
    EXPECT_EQ(json_keys(scene["colliders"][0]), table_keys(collider_settings()));
    EXPECT_EQ(json_keys(scene["kinematic"][0]), table_keys(kinematic_settings()));
    for (const auto& setting : collider_settings()) {
        nlohmann::json j = nlohmann::json::parse(scene.dump());
        j["colliders"][2].erase(setting.key);
        EXPECT_NE(scene_json_error(j).find("scene.colliders[2]." + setting.key + " is missing"), std::string::npos)
            << scene_json_error(j);
    }
    for (const auto& setting : kinematic_settings()) {
        nlohmann::json j = nlohmann::json::parse(scene.dump());
        j["kinematic"][1].erase(setting.key);
        EXPECT_NE(scene_json_error(j).find("scene.kinematic[1]." + setting.key + " is missing"), std::string::npos)
            << scene_json_error(j);
    }

    ObjectSettings object;
    object.driven.resize(2);
    object.driven[0].piece = 3;
    object.driven[0].velocity = Vec3(0.5, 0, 0);
    object.driven[1].piece = 4;
    object.driven[1].keys = {{0, Vec3(0, 1, 0)}, {1.5, Vec3(0, 2, 0.25)}};
    const nlohmann::ordered_json driven = to_json(object)["driven"];
    EXPECT_EQ(json_keys(driven[0]), table_keys(driven_settings()));
    nlohmann::json parent = {{"driven", nlohmann::json::parse(driven.dump())}};
    JsonObject o(parent, "t.traj", "object");
    const std::vector<PieceDriveSettings> back = entries_from_json(driven_settings(), o, "driven");
    EXPECT_EQ(entries_json(driven_settings(), back).dump(), driven.dump());
    EXPECT_EQ(back[1].keys[1].position, Vec3(0, 2, 0.25));
    parent["driven"][0]["piece"] = -1;
    JsonObject bad(parent, "t.traj", "object");
    try {
        entries_from_json(driven_settings(), bad, "driven");
        ADD_FAILURE() << "a negative piece was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("object.driven[0].piece must be a whole number from 0 to 4294967295"),
                  std::string::npos)
            << e.what();
    }
}

// A key added to an entry's table with .json_unless_default() keeps the bytes of the files written
// before it, and those files read back with its default.
TEST(SceneSettings, AnEntryKeyWrittenUnlessDefaultReadsBackWhenAbsent) {
    std::vector<BasicSetting<ColliderSettings>> table = collider_settings();
    for (auto& setting : table)
        if (setting.key == "radius") setting.json_unless_default();
    std::vector<ColliderSettings> colliders(2);
    colliders[1].shape.kind = ShapeKind::Sphere;
    colliders[1].shape.radius = 0.25;
    const nlohmann::ordered_json written = entries_json(table, colliders);
    EXPECT_FALSE(written[0].contains("radius"));
    EXPECT_EQ(written[1]["radius"], 0.25);
    nlohmann::json parent = {{"colliders", nlohmann::json::parse(written.dump())}};
    JsonObject o(parent, "t.traj", "scene");
    const std::vector<ColliderSettings> back = entries_from_json(table, o, "colliders");
    EXPECT_EQ(back[0].shape.radius, ColliderSettings{}.shape.radius);
    EXPECT_EQ(back[1].shape.radius, 0.25);
    EXPECT_EQ(entries_json(table, back).dump(), written.dump());
}

// A kinematic body's mesh and mesh_scale are in its JSON (its shape written as a collider's) but
// are not keys of the shot file nor of its docs table.
TEST(SceneShot, AKinematicBodysMeshKeysAreInItsJsonOnly) {
    expect_error("[[scene.kinematic]]\nmesh = \"a.obj\"\n", {"s.toml:2", "unknown key 'scene.kinematic[0].mesh'"});
    expect_error("[[scene.kinematic]]\nmesh_scale = 2\n", {"s.toml:2", "unknown key 'scene.kinematic[0].mesh_scale'"});
    EXPECT_EQ(settings_markdown("scene.kinematic").find("| mesh"), std::string::npos);
    EXPECT_NE(to_json(busy_scene())["kinematic"][0].dump().find(R"("mesh":"","mesh_scale":1.0)"), std::string::npos);
}

TEST(SceneSettings, OtherSectionsWriteEveryFieldWithEnumsAsStrings) {
    SimulateSettings sim;
    EXPECT_EQ(to_json(sim).dump(), R"({"duration":4.0,"fps":30.0,"substeps":8,"iterations":20,"energy_split":"total",)"
                                   R"("directions":"opposed","kick_bodies":"joined","rate_limit":0.0,"rollback":false,)"
                                   R"("exact_energy":true,"seed":1,"max_cfm":0.5})");
    apply_energize_method(EnergizeMethod::Paper, sim);
    EXPECT_EQ(to_json(sim).dump(), R"({"duration":4.0,"fps":30.0,"substeps":8,"iterations":20,"method":"paper",)"
                                   R"("energy_split":"per_body","directions":"paper","kick_bodies":"pieces","rate_limit":0.0,)"
                                   R"("rollback":false,)"
                                   R"("exact_energy":false,"seed":1,"max_cfm":0.5})");
    MaterialSettings mat;
    EXPECT_EQ(to_json(mat).dump(), R"({"density":null,"stiffness":10000000000.0,"damping":0.0,"strength":1000000.0,)"
                                   R"("alpha":1.0,"friction":0.5,"restitution":0.1})");
    mat.density = 2500;
    EXPECT_EQ(to_json(mat)["density"], 2500.0);
    EXPECT_EQ(to_json(ObjectSettings{}).dump(),
              R"({"position":[0.0,0.0,0.0],"rotation":[0.0,0.0,0.0],"velocity":[0.0,0.0,0.0],)"
              R"("angular_velocity":[0.0,0.0,0.0],"driven":[]})");
    EXPECT_STREQ(to_string(KickDirectionMode::Opposed), "opposed");
    EXPECT_STREQ(to_string(KickDirectionMode::Force), "force");
    EXPECT_STREQ(to_string(EnergySplitMode::Total), "total");
    EXPECT_STREQ(to_string(ShapeKind::Mesh), "mesh");
}

}  // namespace
}  // namespace shatter

namespace shatter {
namespace {

TEST(SceneShot, DrivenPiecesAreReadAndTheirOffsetsFollowVelocityOrKeys) {
    testing_support::TempDir dir;
    const Shot shot = load_shot(dir.write("s.toml", R"([object]
[[object.driven]]
piece = 0
fixed = true
[[object.driven]]
piece = 7
velocity = [0.05, 0, 0]
[[object.driven]]
piece = 8
keys = [[0, 0, 0, 0], [2, 0, 1, 0]]
)"));
    ASSERT_EQ(shot.object.driven.size(), 3u);
    EXPECT_TRUE(shot.object.driven[0].fixed);
    EXPECT_EQ(drive_offset(shot.object.driven[0], 5.0), Vec3::Zero());
    EXPECT_EQ(shot.object.driven[1].piece, 7u);
    EXPECT_LT((drive_offset(shot.object.driven[1], 2.0) - Vec3(0.1, 0, 0)).norm(), 1e-15);
    EXPECT_LT((drive_offset(shot.object.driven[2], 1.0) - Vec3(0, 0.5, 0)).norm(), 1e-15);
    EXPECT_LT((drive_offset(shot.object.driven[2], 9.0) - Vec3(0, 1, 0)).norm(), 1e-15);
    EXPECT_EQ(to_json(shot.object)["driven"].size(), 3u);
}

TEST(SceneShot, DrivenPieceWithTwoMotionsOrAnUnknownKeyIsRefused) {
    expect_error("[object]\n[[object.driven]]\npiece = 1\nvelocity = [1, 0, 0]\nkeys = [[0, 0, 0, 0]]\n",
                 {"object.driven[0].keys", "both given"});
    expect_error("[object]\n[[object.driven]]\npiece = 1\nfixed = true\nvelocity = [1, 0, 0]\n", {"fixed", "does not move"});
    expect_error("[object]\n[[object.driven]]\npeice = 1\n", {":3", "object.driven[0].peice", "did you mean 'piece'"});
}

TEST(SceneShot, DurationAutoRunsUntilRestWithACap) {
    TempDir dir;
    const Shot a = load_shot(dir.write("a.toml", "[simulate]\nduration = \"auto\"\nmax_duration = 7.5\n"));
    EXPECT_TRUE(a.simulate.auto_duration);
    EXPECT_DOUBLE_EQ(a.simulate.max_duration, 7.5);
    EXPECT_EQ(to_json(a.simulate)["duration"], "auto");
    EXPECT_EQ(to_json(a.simulate)["max_duration"], 7.5);
    // Seconds are kept as before, and the JSON has no trace of "auto" (trajectories keep their bytes).
    const Shot b = load_shot(dir.write("b.toml", "[simulate]\nduration = 2\n"));
    EXPECT_FALSE(b.simulate.auto_duration);
    EXPECT_FALSE(to_json(b.simulate).contains("max_duration"));
    // An override's seconds replace the shot's "auto".
    EXPECT_FALSE(load_shot(dir.file("a.toml"), {"simulate.duration=0.2"}).simulate.auto_duration);
    expect_error("[simulate]\nduration = \"long\"\n", {"s.toml:2", "simulate.duration", "\"auto\""});
    expect_error("[simulate]\nduration = \"auto\"\nmax_duration = 0\n", {"s.toml:3", "max_duration"});
}

TEST(SceneShot, RenderCameraModeIsReadAndOnlyInTheJsonWithoutAPosition) {
    TempDir dir;
    const Shot a = load_shot(dir.write("a.toml", "[render]\ncamera = \"whole\"\n"));
    EXPECT_EQ(a.render.camera, CameraMode::Whole);
    EXPECT_EQ(to_json(a.render)["camera"], "whole");
    EXPECT_EQ(load_shot(dir.write("b.toml", "[render]\nfov = 30\n")).render.camera, CameraMode::Follow);
    const Shot c = load_shot(dir.write("c.toml", "[render]\ncamera_position = [1, 1, 1]\n"));
    EXPECT_FALSE(to_json(c.render).contains("camera"));
    expect_error("[render]\ncamera = \"orbit\"\n", {"s.toml:2", "not a camera mode", "follow"});
}

}  // namespace
}  // namespace shatter
