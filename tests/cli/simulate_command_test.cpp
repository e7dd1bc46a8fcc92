// `shatter simulate` driven like a user drives it: outputs, determinism, flags over the shot, and
// bad input refused with a clear message and nothing written.
#include <gtest/gtest.h>

#include "core/trajectory.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::run_shatter;
using testing_support::slurp;
using testing_support::TempDir;

const std::string kFixture = SHATTER_SOURCE_DIR "/tests/fixtures/model-v1.model";

// The 10 cm fixture cube (2 pieces) dropped from 0.5 m on the ground, short.
const char* kDropShot = R"([object]
position = [0, 0.5, 0]
[material]
stiffness = 1e12
strength = 2e5
[simulate]
duration = 0.5
)";

TEST(SimulateCommand, WritesTrajectoryBreakLogAndEnergyAndSaysSo) {
    TempDir dir;
    const std::string shot = dir.write("drop.toml", kDropShot);
    auto r = run_shatter({"simulate", kFixture, "--shot", shot, "-o", dir.file("out/cube.traj")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Trajectory t = load_trajectory(dir.file("out/cube.traj"));
    EXPECT_EQ(t.pieces, 2u);
    EXPECT_EQ(t.frames(), 16u);  // 0.5 s at 30 fps, frame 0 included
    EXPECT_TRUE(t.complete);
    const std::string energy = slurp(dir.file("out/cube.energy.csv"));
    EXPECT_EQ(energy.substr(0, energy.find('\n')), "time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J,elastic_J,joint_residual,"
                                                      "joints_damped_J,contacts_J,driven_J,integration_J");
    EXPECT_NE(r.out.find("wrote:"), std::string::npos);
    EXPECT_NE(r.out.find("cube.breaks.jsonl"), std::string::npos);
}

TEST(SimulateCommand, TwoRunsGiveIdenticalBytes) {
    TempDir dir;
    const std::string shot = dir.write("drop.toml", kDropShot);
    for (const char* name : {"a.traj", "b.traj"})
        ASSERT_EQ(run_shatter({"simulate", kFixture, "--shot", shot, "-o", dir.file(name)}).exit_code, 0);
    EXPECT_EQ(slurp(dir.file("a.traj")), slurp(dir.file("b.traj")));
    EXPECT_EQ(slurp(dir.file("a.breaks.jsonl")), slurp(dir.file("b.breaks.jsonl")));
    EXPECT_EQ(slurp(dir.file("a.energy.csv")), slurp(dir.file("b.energy.csv")));
}

TEST(SimulateCommand, AlphaFlagOverridesTheShot) {
    TempDir dir;
    const std::string shot = dir.write("drop.toml", std::string(kDropShot) + "[material]\n");
    // The shot above repeats [material]: TOML refuses that, so write alpha into a fresh shot.
    const std::string s2 = dir.write("s2.toml", "[material]\nalpha = 0.5\nstiffness = 1e12\n[simulate]\nduration = 0.1\n");
    auto r = run_shatter({"simulate", kFixture, "--shot", s2, "--alpha", "2", "-o", dir.file("a.traj")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(slurp(dir.file("a.traj")).find("\"alpha\":2.0"), std::string::npos);
    EXPECT_EQ(run_shatter({"simulate", kFixture, "--shot", shot}).exit_code, 3);  // duplicate table: file:line error
}

TEST(SimulateCommand, SetOverridesTheShotLikeItsFlagAndRefusesSectionsSimulateDoesNotRead) {
    TempDir dir;
    const std::string shot = dir.write("s.toml", "[material]\nalpha = 0.5\nstiffness = 1e12\n[simulate]\nduration = 0.1\n");
    auto r = run_shatter({"simulate", kFixture, "--shot", shot, "--set", "material.alpha=2", "-o", dir.file("a.traj")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(run_shatter({"simulate", kFixture, "--shot", shot, "--alpha", "2", "-o", dir.file("b.traj")}).exit_code, 0);
    EXPECT_EQ(slurp(dir.file("a.traj")), slurp(dir.file("b.traj")));  // the flag is an alias of the key
    r = run_shatter({"simulate", kFixture, "--shot", shot, "--set", "render.width=640"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--set render.width=640: shatter simulate does not read [render]"), std::string::npos) << r.err;
    r = run_shatter({"simulate", kFixture, "--set", "simulate.fps=0"});
    EXPECT_EQ(r.exit_code, 3);  // checked like the file's own value, as `run --set` is
    EXPECT_NE(r.err.find("--set simulate.fps=0: simulate.fps = 0 is outside"), std::string::npos) << r.err;
}

TEST(SimulateCommand, OnInstabilityFlagOverridesTheShotAndIsRecorded) {
    TempDir dir;
    const std::string shot = dir.write("s.toml", "[material]\nstiffness = 1e12\n[simulate]\nduration = 0.1\n");
    auto r = run_shatter({"simulate", kFixture, "--shot", shot, "--on-instability", "clamp", "-o", dir.file("c.traj")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(slurp(dir.file("c.traj")).find("\"on_instability\":\"clamp\""), std::string::npos);
    r = run_shatter({"simulate", kFixture, "--shot", shot, "-o", dir.file("s.traj")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(slurp(dir.file("s.traj")).find("on_instability"), std::string::npos);  // the default keeps old bytes
    EXPECT_EQ(run_shatter({"simulate", kFixture, "--on-instability", "ignore"}).exit_code, 2);
}

struct BadCase {
    const char* name;
    std::string shot;                 // "" = no shot
    std::vector<std::string> flags;
    int damage;                       // 0: the fixture as is; 1: truncated; 2: newer version; 3: not a model
    int exit_code;
    const char* expect;
};

class SimulateBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SimulateBadInput, ClearMessageNonZeroExitNoOutputLeft) {
    const BadCase& c = GetParam();
    TempDir in, out;
    std::string model = slurp(kFixture);
    if (c.damage == 1) model.resize(model.size() / 2);
    if (c.damage == 2) model[8] = 7;
    if (c.damage == 3) model = "v 0 0 0\n";
    const std::string model_path = in.write("m.model", model);
    std::vector<std::string> args = {"simulate", model_path, "-o", out.file("t.traj")};
    if (!c.shot.empty()) args.insert(args.end(), {"--shot", in.write("s.toml", c.shot)});
    args.insert(args.end(), c.flags.begin(), c.flags.end());
    auto r = run_shatter(args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_TRUE(out.entries().empty());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SimulateBadInput,
    ::testing::Values(
        BadCase{"TruncatedModel", "", {}, 1, 3, "m.model"},
        BadCase{"NewerModelVersion", "", {}, 2, 3, "newer than this shatter reads"},
        BadCase{"NotAModel", "", {}, 3, 3, "not a shatter model file"},
        BadCase{"NanStiffness", "[material]\nstiffness = nan\n", {}, 0, 3, "s.toml:2"},
        BadCase{"NegativeStiffness", "[material]\nstiffness = -5\n", {}, 0, 3, "material.stiffness = -5"},
        BadCase{"NegativeAlphaFlag", "", {"--alpha=-1"}, 0, 2, "--alpha"},
        BadCase{"UnknownShotKey", "[simulate]\nsubstep = 4\n", {}, 0, 3, "did you mean 'substeps'"},
        BadCase{"CfmOutsideTheConvergentRange", "[material]\nstiffness = 1\n[simulate]\njoints = \"iterative\"\n", {}, 0, 3,
                "CFM"},
        BadCase{"DrivenPieceThatDoesNotExist", "[object]\n[[object.driven]]\npiece = 9\nfixed = true\n", {}, 0, 3,
                "piece 9 does not exist"}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace shatter
