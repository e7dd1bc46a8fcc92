// `shatter render` and `shatter diff` driven like a user drives them: every frame written with
// zero-padded names, the same bytes for any thread count and range, settings from the shot with
// flags over them, every class of bad input with its exit code and no half-written PNG, and
// every tolerance flag of diff doing what it says.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>

#include "core/scene_settings.h"
#include "render/png_io.h"
#include "scenes/render_test_scene.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using namespace testing_support;
namespace fs = std::filesystem;

// The test scene's trajectory, saved with its scene in the settings as simulate writes it.
// `still_from`: every frame from it on holds that frame's poses (the pieces at rest).
std::string save_test_trajectory(const TempDir& dir, uint32_t frames = 24, uint32_t still_from = UINT32_MAX) {
    TestScene t;
    Trajectory traj = test_trajectory(t.model, t.settings, frames);
    for (uint32_t f = still_from; f < frames; ++f)
        for (uint32_t b = 0; b < traj.bodies(); ++b) traj.poses[size_t(f) * traj.bodies() + b] = traj.pose(still_from, b);
    nlohmann::ordered_json j;
    j["scene"] = to_json(t.settings);
    traj.settings_json = j.dump();
    const std::string path = dir.file("t.traj");
    save_trajectory(path, traj);
    return path;
}

// Runs shatter with LP_NUM_THREADS set for the child only.
CommandResult run_with_threads(const char* threads, const std::vector<std::string>& args) {
    const char* old = std::getenv("LP_NUM_THREADS");
    const std::string saved = old ? old : "";
    ::setenv("LP_NUM_THREADS", threads, 1);
    CommandResult r = run_shatter(args);
    if (old) ::setenv("LP_NUM_THREADS", saved.c_str(), 1); else ::unsetenv("LP_NUM_THREADS");
    return r;
}

std::vector<std::string> pngs_in(const std::string& dir) {
    std::vector<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(RenderCommand, WritesEveryFrameWithZeroPaddedNames) {
    TempDir dir;
    const std::string traj = save_test_trajectory(dir);
    auto r = run_shatter({"render", fixture_model_path(), traj, "-o", dir.file("frames"), "--size", "160x90"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto files = pngs_in(dir.file("frames"));
    ASSERT_EQ(files.size(), 24u);
    EXPECT_EQ(files.front(), "frame_00000.png");
    EXPECT_EQ(files.back(), "frame_00023.png");
    const Image img = load_png(dir.file("frames/frame_00012.png"));
    EXPECT_EQ(img.width, 160u);
    EXPECT_EQ(img.height, 90u);
    EXPECT_NE(r.out.find("24 frames"), std::string::npos) << r.out;
}

TEST(RenderCommand, AFrameIsTheSameBytesForAnyThreadCountAndRange) {
    TempDir dir;
    const std::string traj = save_test_trajectory(dir);
    const std::string m = fixture_model_path();
    auto a = run_with_threads("1", {"render", m, traj, "-o", dir.file("one"), "--size", "320x180", "--frames", "5:8"});
    auto b = run_with_threads("2", {"render", m, traj, "-o", dir.file("two"), "--size", "320x180", "--frames", "0:10"});
    auto c = run_with_threads("2", {"render", m, traj, "-o", dir.file("again"), "--size", "320x180", "--frames", "6:7"});
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_EQ(pngs_in(dir.file("one")), (std::vector<std::string>{"frame_00005.png", "frame_00006.png", "frame_00007.png"}));
    for (const char* f : {"frame_00005.png", "frame_00006.png", "frame_00007.png"})
        EXPECT_EQ(slurp(dir.file(std::string("one/") + f)), slurp(dir.file(std::string("two/") + f))) << f;
    EXPECT_EQ(slurp(dir.file("again/frame_00006.png")), slurp(dir.file("two/frame_00006.png")));
    EXPECT_NE(slurp(dir.file("two/frame_00005.png")), slurp(dir.file("two/frame_00006.png")));  // it moves
}

// Frames whose pieces rest where the frame before had them, the camera still, are that frame's PNG
// written again, without drawing: the same bytes as the frame drawn on its own.
TEST(RenderCommand, AFrameThatDrawsWhatTheOneBeforeDrewIsItsBytesAgain) {
    TempDir dir;
    const std::string traj = save_test_trajectory(dir, 48, 8);
    const std::string m = fixture_model_path();
    auto all = run_shatter({"render", m, traj, "-o", dir.file("all"), "--size", "320x180", "--frames", "0:48"});
    ASSERT_EQ(all.exit_code, 0) << all.err;
    EXPECT_NE(all.out.find("the same picture as the frame before"), std::string::npos) << all.out;
    for (const std::string f : {"00040", "00047"}) {
        const std::string range = std::to_string(std::stoi(f)) + ":" + std::to_string(std::stoi(f) + 1);
        auto one = run_shatter({"render", m, traj, "-o", dir.file(f), "--size", "320x180", "--frames", range});
        ASSERT_EQ(one.exit_code, 0) << one.err;
        EXPECT_EQ(one.out.find("the same picture"), std::string::npos) << one.out;  // drawn
        EXPECT_TRUE(slurp(dir.file(f + "/frame_" + f + ".png")) == slurp(dir.file("all/frame_" + f + ".png"))) << f;
    }
    EXPECT_TRUE(slurp(dir.file("all/frame_00005.png")) != slurp(dir.file("all/frame_00006.png")));  // it moved before
}

TEST(RenderCommand, ShotSectionSetsTheSizeAndFlagsOverrideIt) {
    TempDir dir;
    const std::string traj = save_test_trajectory(dir, 2);
    const std::string shot = dir.write("s.toml", "[render]\nwidth = 200\nheight = 100\nmsaa = 1\n");
    auto r = run_shatter({"render", fixture_model_path(), traj, "-o", dir.file("a"), "--shot", shot});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(load_png(dir.file("a/frame_00000.png")).width, 200u);
    r = run_shatter({"render", fixture_model_path(), traj, "-o", dir.file("b"), "--shot", shot, "--size", "120x60"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(load_png(dir.file("b/frame_00001.png")).height, 60u);
}

TEST(RenderCommand, SetTakesAnyRenderKeyAndItsFlagIsTheSameKey) {
    TempDir dir;
    const std::string traj = save_test_trajectory(dir, 1);
    auto r = run_shatter({"render", fixture_model_path(), traj, "-o", dir.file("a"), "--set", "render.width=150",
                          "--set", "render.height=80", "--set", "render.msaa=1", "--fov", "30"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(load_png(dir.file("a/frame_00000.png")).width, 150u);
    r = run_shatter({"render", fixture_model_path(), traj, "-o", dir.file("b"), "--set", "simulate.fps=3"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("shatter render does not read [simulate]"), std::string::npos) << r.err;
    r = run_shatter({"render", fixture_model_path(), traj, "-o", dir.file("c"), "--fov", "500"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--fov = 500 is outside [1, 170] degrees"), std::string::npos) << r.err;
}

struct BadCase {
    const char* what;
    std::vector<std::string> args;  // after "render MODEL"
    int exit_code;
    const char* mentions;
};

TEST(RenderCommand, BadInputGivesAClearErrorAndNoFrames) {
    TempDir dir;
    const std::string traj = save_test_trajectory(dir, 3);
    const std::string corrupt = dir.write("corrupt.traj", slurp(traj).substr(0, 100));
    TestScene t;
    Trajectory three = test_trajectory(t.model, t.settings, 3);
    three.pieces = 3;
    three.props = 0;
    three.poses.resize(3 * 3);
    save_trajectory(dir.file("three.traj"), three);
    dir.write("a-file", "x");
    const std::string out = dir.file("out");
    const BadCase cases[] = {
        {"missing trajectory", {dir.file("none.traj"), "-o", out}, 3, "none.traj"},
        {"corrupt trajectory", {corrupt, "-o", out}, 3, "corrupt.traj"},
        {"another model's trajectory", {dir.file("three.traj"), "-o", out}, 3, "3 pieces"},
        {"size 0", {traj, "-o", out, "--size", "0x100"}, 2, "--size"},
        {"size beyond GL", {traj, "-o", out, "--size", "100x40000"}, 2, "--size"},
        {"size not a size", {traj, "-o", out, "--size", "big"}, 2, "--size"},
        {"frames outside", {traj, "-o", out, "--frames", "2:9"}, 2, "--frames"},
        {"msaa 3", {traj, "-o", out, "--msaa", "3"}, 2, "msaa"},
        {"bad colour", {traj, "-o", out, "--background", "blue"}, 2, "--background"},
        {"unwritable output", {traj, "-o", dir.file("a-file/frames")}, 4, "a-file"},
    };
    for (const BadCase& c : cases) {
        std::vector<std::string> args = {"render", fixture_model_path()};
        args.insert(args.end(), c.args.begin(), c.args.end());
        auto r = run_shatter(args);
        EXPECT_EQ(r.exit_code, c.exit_code) << c.what << ": " << r.err;
        EXPECT_NE(r.err.find(c.mentions), std::string::npos) << c.what << ": " << r.err;
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << c.what << ": " << r.err;
        EXPECT_TRUE(pngs_in(out).empty()) << c.what << " left files behind";
    }
}

// --- shatter diff ---

// A 100x50 grey image, and the same with one channel of one pixel 60 levels higher:
// max 60, rmse = 60 / sqrt(15000) = 0.49, psnr 54.3 dB, ssim 0.99745, 0.02% of pixels over 8 levels.
struct DiffPair {
    TempDir dir;
    std::string a, b;
    DiffPair() {
        Image img(100, 50);
        std::fill(img.rgb.begin(), img.rgb.end(), uint8_t(100));
        fs::create_directories(dir.file("a"));
        fs::create_directories(dir.file("b"));
        save_png(a = dir.file("a/frame_00000.png"), img);
        img.pixel(10, 20)[1] = 160;
        save_png(b = dir.file("b/frame_00000.png"), img);
    }
};

int diff_exit(const DiffPair& p, std::vector<std::string> flags) {
    std::vector<std::string> args = {"diff", p.a, p.b, "--no-report"};
    args.insert(args.end(), flags.begin(), flags.end());
    return run_shatter(args).exit_code;
}

TEST(DiffCommand, EveryToleranceFlagDecides) {
    DiffPair p;
    EXPECT_EQ(diff_exit(p, {}), 0);  // within the default tolerance
    EXPECT_EQ(diff_exit(p, {"--max-channel-diff", "59"}), 1);
    EXPECT_EQ(diff_exit(p, {"--max-channel-diff", "60"}), 0);
    EXPECT_EQ(diff_exit(p, {"--max-rmse", "0.48"}), 1);
    EXPECT_EQ(diff_exit(p, {"--max-rmse", "0.5"}), 0);
    EXPECT_EQ(diff_exit(p, {"--min-psnr", "55"}), 1);
    EXPECT_EQ(diff_exit(p, {"--min-psnr", "54"}), 0);
    EXPECT_EQ(diff_exit(p, {"--min-ssim", "0.998"}), 1);  // ssim is 0.99745
    EXPECT_EQ(diff_exit(p, {"--min-ssim", "0.997"}), 0);
    EXPECT_EQ(diff_exit(p, {"--max-fraction", "0.0001"}), 1);
    EXPECT_EQ(diff_exit(p, {"--max-fraction", "0.0002"}), 0);
    EXPECT_EQ(diff_exit(p, {"--max-fraction", "0", "--threshold", "59"}), 1);
    EXPECT_EQ(diff_exit(p, {"--max-fraction", "0", "--threshold", "60"}), 0);
    EXPECT_EQ(diff_exit(p, {"--max-rmse", "-1"}), 2);  // a flag out of range
}

TEST(DiffCommand, DirectoriesGiveHeatMapsSummaryAndJunit) {
    DiffPair p;
    const std::string report = p.dir.file("report"), junit = p.dir.file("r.xml");
    auto same = run_shatter({"diff", p.dir.file("a"), p.dir.file("a"), "--report", report});
    EXPECT_EQ(same.exit_code, 0) << same.err;
    auto r = run_shatter({"diff", p.dir.file("a"), p.dir.file("b"), "--report", report, "--max-channel-diff", "10",
                          "--junit", junit});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.out.find("DIFFERS frame_00000.png"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(report + "/frame_00000.heat.png"));
    const std::string json = slurp(report + "/summary.json");
    EXPECT_NE(json.find("\"failed\": 1"), std::string::npos) << json;
    EXPECT_NE(json.find("\"max_channel_diff\": 60"), std::string::npos) << json;
    const std::string xml = slurp(junit);
    EXPECT_NE(xml.find("<failure message=\"max channel difference 60 &gt; 10\""), std::string::npos) << xml;
}

TEST(DiffCommand, MissingFrameSizeMismatchAndUnreadableFileExit2) {
    DiffPair p;
    Image small(10, 10);
    save_png(p.dir.file("small.png"), small);
    p.dir.write("b/frame_00001.png", "not a png");
    p.dir.write("broken.png", "not a png");
    EXPECT_EQ(run_shatter({"diff", p.a, p.dir.file("small.png"), "--no-report"}).exit_code, 2);
    EXPECT_EQ(run_shatter({"diff", p.a, p.dir.file("broken.png"), "--no-report"}).exit_code, 2);
    auto missing = run_shatter({"diff", p.dir.file("a"), p.dir.file("b"), "--no-report"});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("frame_00001.png"), std::string::npos) << missing.err;
    EXPECT_EQ(run_shatter({"diff", p.a, p.dir.file("nothing.png"), "--no-report"}).exit_code, 2);
}

}  // namespace
}  // namespace shatter
