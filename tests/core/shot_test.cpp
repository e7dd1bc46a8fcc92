#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/shot.h"
#include "support/shot_error.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

std::string load_error(const std::string& path) { return testing_support::shot_load_error(path); }

TEST(ShotFile, ReadsEverySettingAndResolvesTheMeshBesideTheShot) {
    TempDir dir;
    std::string path = dir.write("a.toml", R"(# a comment
[mesh]
path = "models/bunny.obj"  # relative to the shot
scale = 0.1
repair = "never"

[prescore]
pieces = 7
seed = 42
hollow = "12mm"
resolution = 25
density = 1000
)");
    Shot s = load_shot(path);
    EXPECT_EQ(s.mesh.path, dir.file("models/bunny.obj"));
    ASSERT_TRUE(s.mesh.scale.has_value());
    EXPECT_DOUBLE_EQ(*s.mesh.scale, 0.1);
    EXPECT_FALSE(s.mesh.size.has_value());
    EXPECT_EQ(s.mesh.repair, RepairMode::Never);
    EXPECT_EQ(s.prescore.pieces, 7u);
    EXPECT_EQ(s.prescore.seed, 42u);
    ASSERT_TRUE(s.prescore.hollow.has_value());
    EXPECT_FALSE(s.prescore.hollow->relative);
    EXPECT_DOUBLE_EQ(s.prescore.hollow->value, 0.012);
    EXPECT_DOUBLE_EQ(s.prescore.resolution, 25);
    EXPECT_DOUBLE_EQ(s.prescore.density, 1000);
}

TEST(ShotFile, ASizeOrNoScaleLeavesTheScaleToTheFileOrTheDefaultSize) {
    TempDir dir;
    Shot s = load_shot(dir.write("a.toml", "[mesh]\npath = \"m.obj\"\nsize = 0.25\nadapt = false\n"));
    ASSERT_TRUE(s.mesh.size.has_value());
    EXPECT_DOUBLE_EQ(*s.mesh.size, 0.25);
    EXPECT_FALSE(s.mesh.scale.has_value());
    EXPECT_FALSE(s.mesh.adapt);
    EXPECT_EQ(to_json(s.mesh)["scale"], "auto");
    EXPECT_NE(load_error(dir.write("b.toml", "[mesh]\npath = \"m.obj\"\nsize = 0\n")).find("mesh.size"),
              std::string::npos);
}

// `shatter run MESH` runs the default shot, which is assets/bunny.toml without its mesh path,
// scale and camera, with the mesh's base placed: every other setting must agree.
TEST(ShotFile, TheDefaultShotForAMeshIsTheDemoShotWithoutItsMeshAndCamera) {
    const Shot demo = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/bunny.toml");
    const Shot mine = default_shot_for_mesh("horse.3ds", {"material.alpha=2"});
    EXPECT_EQ(mine.mesh.path, "horse.3ds");
    EXPECT_FALSE(mine.mesh.scale.has_value());
    EXPECT_FALSE(mine.mesh.size.has_value());
    EXPECT_DOUBLE_EQ(mine.material.alpha, 2);
    EXPECT_EQ(to_json(mine.prescore), to_json(demo.prescore));
    EXPECT_EQ(to_json(mine.scene), to_json(demo.scene));
    EXPECT_EQ(mine.object.place, Placement::Base);
    Shot placed = mine;
    placed.object.place = Placement::Origin;
    EXPECT_EQ(to_json(placed.object), to_json(demo.object));
    Shot alpha1 = default_shot_for_mesh("horse.3ds");
    EXPECT_TRUE(alpha1.material.stiffen);
    alpha1.material.stiffen = false;
    EXPECT_EQ(to_json(alpha1.material), to_json(demo.material));
    EXPECT_EQ(to_json(alpha1.simulate), to_json(demo.simulate));
    RenderSettings render = demo.render;
    render.camera_position.reset();
    render.camera_target.reset();
    EXPECT_EQ(to_json(alpha1.render), to_json(render));
    EXPECT_EQ(mine.mesh.repair, demo.mesh.repair);
    EXPECT_EQ(mine.mesh.wrap_alpha, demo.mesh.wrap_alpha);
    EXPECT_EQ(mine.mesh.wrap_offset, demo.mesh.wrap_offset);
    EXPECT_EQ(load_shot_or_mesh("horse.3ds").mesh.path, "horse.3ds");
}

// Every shot takes the automatic step unless it names one, whatever the material: a real
// material's joints are too stiff for a fixed step (omega h in the hundreds at 1/480 s), and the
// demo's weak cast (E = 0.2 GPa) runs one step a block where its joints are calm. Its joints are
// "auto", which solves them directly at any piece count. What the user chooses wins.
TEST(ShotFile, EveryShotTakesTheAutomaticStepAndDirectJointsUnlessItNamesThem) {
    for (const char* material : {"material.preset=porcelain", "material.youngs_modulus=1e9",
                                 "material.preset=weak_cast", "material.youngs_modulus=9.9e8"}) {
        const Shot s = default_shot_for_mesh("horse.3ds", {material});
        EXPECT_TRUE(s.simulate.auto_substeps) << material;
        EXPECT_EQ(s.simulate.joints, JointSolve::Auto) << material;
    }
    const Shot step = default_shot_for_mesh("horse.3ds", {"material.preset=glass", "simulate.substeps=64"});
    EXPECT_FALSE(step.simulate.auto_substeps);
    EXPECT_EQ(step.simulate.substeps, 64u);
    EXPECT_EQ(step.simulate.joints, JointSolve::Auto);
    const Shot joints = default_shot_for_mesh("horse.3ds", {"material.preset=glass", "simulate.joints=iterative"});
    EXPECT_TRUE(joints.simulate.auto_substeps);
    EXPECT_EQ(joints.simulate.joints, JointSolve::Iterative);
    // A shot file's settings are taken as written: one that names its step keeps it.
    TempDir dir;
    const Shot named = load_shot(dir.write("step.toml", "[mesh]\npath = \"m.obj\"\n[simulate]\nsubsteps = 1000\n"));
    EXPECT_FALSE(named.simulate.auto_substeps);
    EXPECT_EQ(named.simulate.substeps, 1000u);
    // A shot file that chooses neither the step nor the joint solve, whatever its material.
    const std::string file = dir.write("s.toml", "[mesh]\npath = \"m.obj\"\n[material]\npreset = \"porcelain\"\n");
    const Shot unset = load_shot(file);
    EXPECT_TRUE(unset.simulate.auto_substeps);
    EXPECT_EQ(unset.simulate.joints, JointSolve::Auto);
    EXPECT_FALSE(load_shot(file, {"simulate.substeps=8"}).simulate.auto_substeps);
    EXPECT_EQ(load_shot(file, {"simulate.joints=iterative"}).simulate.joints, JointSolve::Iterative);
    EXPECT_TRUE(load_shot(file, {"material.preset=weak_cast"}).simulate.auto_substeps);
    EXPECT_TRUE(load_shot(file, {"material.youngs_modulus=1e6"}).simulate.auto_substeps);
}

TEST(ShotFile, UnknownKeyNamesFileLineAndSuggestsTheKnownKey) {
    TempDir dir;
    std::string path = dir.write("a.toml", "[prescore]\npieces = 3\npeices = 4\n");
    std::string m = load_error(path);
    EXPECT_NE(m.find(path + ":3"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown key 'prescore.peices'"), std::string::npos) << m;
    EXPECT_NE(m.find("did you mean 'pieces'"), std::string::npos) << m;
}

TEST(ShotFile, ARenamedKeyNamesItsNewNameAndHowToWriteItsValue) {
    TempDir dir;
    std::string path = dir.write("a.toml", "[render]\nwidth = 320\ncolour_mode = \"pieces\"\n");
    std::string m = load_error(path);
    EXPECT_NE(m.find(path + ":3"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown key 'render.colour_mode'"), std::string::npos) << m;
    EXPECT_NE(m.find("colour_mode was renamed colours"), std::string::npos) << m;
    EXPECT_NE(m.find("colours = \"palette\""), std::string::npos) << m;
}

TEST(ShotFile, SeedPointsAreReadAsPointsAndABadOneNamesFileLineAndIndex) {
    TempDir dir;
    const Shot s = load_shot(dir.write("a.toml", "[prescore]\nseeds = \"points\"\nseed_points = [[0.1, 0.2, 0.3], [0, 0, -1]]\n"));
    EXPECT_EQ(s.prescore.seeds, SeedMode::Points);
    ASSERT_EQ(s.prescore.seed_points.size(), 2u);
    EXPECT_EQ(s.prescore.seed_points[0][1], 0.2);
    EXPECT_EQ(s.prescore.seed_points[1][2], -1);
    EXPECT_NE(s.prescore.seed_points_where.find("a.toml:3"), std::string::npos);
    EXPECT_FALSE(s.prescore.impact_ratio);  // "auto"
    const std::string path = dir.write("b.toml", "[prescore]\nseed_points = [[0.1, 0.2, 0.3], [1, 2]]\n");
    const std::string m = load_error(path);
    EXPECT_NE(m.find(path + ":2"), std::string::npos) << m;
    EXPECT_NE(m.find("prescore.seed_points[1] must be an array of 3 numbers [x, y, z]"), std::string::npos) << m;
    EXPECT_NE(load_error(dir.write("c.toml", "[prescore]\nimpact_radius = \"wide\"\n")).find("impact_radius = \"auto\""),
              std::string::npos);
    EXPECT_EQ(load_shot(dir.write("d.toml", "[prescore]\nimpact_ratio = 5\nimpact_radius = \"2cm\"\n")).prescore.impact_radius->str(),
              "0.02m");
}

TEST(ShotFile, UnknownSectionIsAnError) {
    TempDir dir;
    std::string m = load_error(dir.write("a.toml", "[mesh]\nscale = 1\n\n[prescor]\npieces = 3\n"));
    EXPECT_NE(m.find(":4"), std::string::npos) << m;
    EXPECT_NE(m.find("did you mean 'prescore'"), std::string::npos) << m;
}

TEST(ShotFile, OutOfRangeValueNamesKeyValueAndRange) {
    TempDir dir;
    std::string m = load_error(dir.write("a.toml", "[prescore]\n\npieces = 0\n"));
    EXPECT_NE(m.find("a.toml:3"), std::string::npos) << m;
    EXPECT_NE(m.find("prescore.pieces = 0 is outside [1, 1e+06]"), std::string::npos) << m;
}

TEST(ShotFile, NanAndWrongTypesAreRefused) {
    TempDir dir;
    EXPECT_NE(load_error(dir.write("a.toml", "[prescore]\ndensity = nan\n")).find("not a finite number"),
              std::string::npos);
    EXPECT_NE(load_error(dir.write("b.toml", "[prescore]\npieces = \"ten\"\n")).find("whole number"),
              std::string::npos);
    EXPECT_NE(load_error(dir.write("c.toml", "[prescore]\nhollow = -0.1\n")).find("outside"), std::string::npos);
    EXPECT_NE(load_error(dir.write("d.toml", "[prescore]\nhollow = \"3 furlongs\"\n")).find("not a length"),
              std::string::npos);
    EXPECT_NE(load_error(dir.write("e.toml", "[mesh]\nrepair = \"maybe\"\n")).find("not a repair mode"),
              std::string::npos);
}

TEST(ShotFile, SyntaxErrorNamesLineAndColumn) {
    TempDir dir;
    std::string m = load_error(dir.write("a.toml", "[mesh]\nscale = = 2\n"));
    EXPECT_NE(m.find("a.toml:2:"), std::string::npos) << m;
}

TEST(ShotFile, MissingFileIsNamed) {
    std::string m = load_error("/nonexistent/shot.toml");
    EXPECT_NE(m.find("/nonexistent/shot.toml"), std::string::npos) << m;
}

TEST(Length, ParsesRelativeAndAbsoluteLengths) {
    EXPECT_TRUE(Length::parse("0.05")->relative);
    EXPECT_DOUBLE_EQ(Length::parse("12mm")->value, 0.012);
    EXPECT_DOUBLE_EQ(Length::parse("1.5cm")->value, 0.015);
    EXPECT_DOUBLE_EQ(Length::parse("2m")->value, 2);
    EXPECT_FALSE(Length::parse("2 m").has_value());
    EXPECT_FALSE(Length::parse("inf").has_value());
    EXPECT_FALSE(Length::parse("").has_value());
    EXPECT_DOUBLE_EQ((Length{0.1, true}.resolve(3.0)), 0.3);
}

}  // namespace
}  // namespace shatter
