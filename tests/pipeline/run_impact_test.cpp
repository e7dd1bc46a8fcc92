// `shatter run MESH` grades the pieces by the impact (the default shot's seeds = "impact"): a cube
// dropped flat from 1.5 m lands on its bottom face at sqrt(2 g 1.5) = 5.42 m/s, and
// the closing summary and summary.json say so.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "pipeline/run.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

// A run of `shot` through prescore and simulate (the summary's model part comes with simulate)
// into DIR/out.
RunOptions to_simulate(const TempDir& dir, const std::string& shot, std::vector<std::string> overrides = {}) {
    RunOptions o;
    o.shot = shot;
    o.output_dir = dir.file("out");
    o.overrides = std::move(overrides);
    o.stages = {Stage::Prescore, Stage::Simulate};
    o.progress = false;
    return o;
}

TEST(RunImpact, TheSummarySaysWhereTheCubeHitAndHowThePiecesWereGraded) {
    TempDir dir;
    const RunResult r = run_shot(to_simulate(dir, SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj"));
    ASSERT_EQ(r.exit_code, 0);
    const auto& impact = r.summary["model"]["impact"];
    ASSERT_TRUE(impact["graded"].get<bool>()) << impact.dump();
    const auto& first = impact["contacts"][0];
    EXPECT_EQ(first["with"].get<std::string>(), "ground");
    EXPECT_TRUE(first["grades"].get<bool>());
    EXPECT_NEAR(first["speed_m_per_s"].get<double>(), std::sqrt(2 * 9.81 * 1.5), 1e-3);
    // The mean of the bottom face's surface vertices: near its middle (Mesh_3 places them), on the ground.
    EXPECT_NEAR(first["point_m"][0].get<double>(), 0, 0.03);
    EXPECT_NEAR(first["point_m"][1].get<double>(), 0, 1e-9);
    EXPECT_NEAR(first["point_m"][2].get<double>(), 0, 0.03);
    // impact_ratio "auto": 1 + 12 D, D = rho v^2 / strength = 1100 x 2 g 1.5 / 2e4 = 1.62 (the default
    // shot's cast): 20.4.
    const double damage = 1100 * 2 * 9.81 * 1.5 / 2e4;
    EXPECT_NEAR(impact["damage_number"].get<double>(), damage, 1e-3);
    EXPECT_NEAR(impact["ratio"].get<double>(), 1 + 12 * damage, 1e-2);
    const std::string closing = format_run_summary(r);
    EXPECT_NE(closing.find("impact:   at ("), std::string::npos) << closing;
    EXPECT_NE(closing.find(" m, speed 5.42 m/s, on the ground after 0.553 s; pieces graded: seeds 20.4 times denser "
                           "there"),
              std::string::npos)
        << closing;
    EXPECT_NE(closing.find("(auto: damage number rho v^2 / strength 1.62)"), std::string::npos) << closing;
}

// The same cube in porcelain (2,400 kg/m^3, 40 MPa): D = 2400 x 2 g 1.5 / 4e7 = 0.0018, impact_ratio
// 1 + 12 D = 1.02, too gentle to grade (prescore/graded_seeds.h): uniform seeds, and the summary
// says where it hit and why the pieces were not graded.
TEST(RunImpact, ACubeTooStrongToBeGradedSaysWhereItHitAndWhyNot) {
    TempDir dir;
    const RunResult r =
        run_shot(to_simulate(dir, SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", {"material.preset=porcelain"}));
    ASSERT_EQ(r.exit_code, 0);
    const auto& impact = r.summary["model"]["impact"];
    EXPECT_FALSE(impact["graded"].get<bool>()) << impact.dump();
    const double damage = 2400 * 2 * 9.81 * 1.5 / 4e7;
    EXPECT_NEAR(impact["damage_number"].get<double>(), damage, 1e-5);
    EXPECT_NEAR(impact["ratio"].get<double>(), 1 + 12 * damage, 1e-4);
    const std::string closing = format_run_summary(r);
    EXPECT_NE(closing.find(" m, speed 5.42 m/s, on the ground after 0.553 s; pieces not graded: uniform seeds (damage "
                           "number rho v^2 / strength 0.00177: impact_ratio 1.02, too gentle)"),
              std::string::npos)
        << closing;
}

// A slab given as a mesh collider (its top at y = 0.3 m) under the cube: the pre-pass's first
// contact is on it, and prescore's stamp holds what the grading read: the slab's file and the
// material (its strength sets the automatic ratio). Either changed, prescore is out of date.
TEST(RunImpact, PrescoreIsOutOfDateWhenTheMeshColliderOrTheMaterialChanges) {
    TempDir dir;
    auto slab = [](double top) {
        std::string obj;
        for (int i = 0; i < 8; ++i)
            obj += fmt::format("v {} {} {}\n", i & 1 ? 0.5 : -0.5, i & 2 ? top : top - 0.05, i & 4 ? 0.5 : -0.5);
        return obj + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    };
    dir.write("slab.obj", slab(0.3));
    const std::string shot = dir.write(
        "drop.toml", "[mesh]\npath = \"" SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj\"\nscale = 0.1\n\n"
                     "[prescore]\npieces = 4\nresolution = 8\nrender_surface = false\nseeds = \"impact\"\n\n"
                     "[object]\nposition = [0, 1, 0]\n\n[material]\nstrength = 2e4\n\n[simulate]\nduration = 0.5\n\n"
                     "[[scene.colliders]]\nname = \"slab\"\nshape = \"mesh\"\nmesh = \"slab.obj\"\n");
    const RunOptions o = to_simulate(dir, shot);
    const RunResult r = run_shot(o);
    ASSERT_EQ(r.exit_code, 0);
    const auto& first = r.summary["model"]["impact"]["contacts"][0];
    EXPECT_EQ(first["with"].get<std::string>(), "slab") << r.summary["model"]["impact"].dump();
    EXPECT_NEAR(first["point_m"][1].get<double>(), 0.3, 1e-6);
    auto prescore_fresh = [&](const RunOptions& options) {
        for (Stage s : up_to_date_stages(options))
            if (s == Stage::Prescore) return true;
        return false;
    };
    EXPECT_TRUE(prescore_fresh(o));
    RunOptions stronger = o;
    stronger.overrides = {"material.strength=4e4"};
    EXPECT_FALSE(prescore_fresh(stronger));
    dir.write("slab.obj", slab(0.2));
    EXPECT_FALSE(prescore_fresh(o));
}

}  // namespace
}  // namespace shatter
