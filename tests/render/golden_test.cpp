// Golden images: three frames of the small test scene (scenes/render_test_scene.h) at
// 320x180 through the whole pipeline (render_frames, PNG writer), compared with the committed
// goldens in tests/golden/render/ (and the same scene with the textured v3 fixture in
// tests/golden/textured/) by the project's own diff at a stated tolerance:
//   RMSE <= 1.5 levels, SSIM >= 0.98, at most 0.5% of pixels off by more than 24 levels.
// The tolerance absorbs rasterizer differences between Mesa versions (a few edge pixels); on
// one machine the renders are byte-identical. Deliberate changes of the look (a moved key light,
// a wrong colour, untinted fracture faces, a moved camera) must fail it.
//
// To re-make the goldens after an intended change of the look, run the test with
// SHATTER_UPDATE_GOLDEN=1 (as `make refresh` does), look at the images, and commit them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "render/diff_report.h"
#include "render/png_io.h"
#include "scenes/render_test_scene.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using namespace testing_support;
namespace fs = std::filesystem;

const DiffTolerance kGoldenTolerance{255, 1.5, 0, 0.98, 24, 0.005};
const uint32_t kGoldenFrames[] = {0, 12, 23};

std::string golden_dir() { return std::string(SHATTER_SOURCE_DIR) + "/tests/golden/render"; }

// The textured goldens: the same scene with the v3 fixture (a textured box in 2 pieces), in the
// input's colours (its texture).
std::string textured_golden_dir() { return std::string(SHATTER_SOURCE_DIR) + "/tests/golden/textured"; }

// Renders the golden frames with `settings` into `dir` (of the v3 fixture when `textured`).
void render_golden_frames(const RenderSettings& settings, const std::string& dir, bool textured = false) {
    TestScene t;
    if (textured) {
        t.model = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v3.model");
        t.trajectory = test_trajectory(t.model, t.settings);
    }
    const RenderScene scene = t.scene();
    RenderOptions quiet;
    quiet.progress = false;
    for (uint32_t f : kGoldenFrames) render_frames(scene, settings, {f, f + 1}, dir, quiet);
}

// Worst result over the golden frames.
DiffSummary compare_with_goldens(const std::string& dir) {
    return diff_paths(golden_dir(), dir, kGoldenTolerance, "");
}

// With SHATTER_UPDATE_GOLDEN set (as `make refresh` sets it), frames in `rendered` that no longer
// match the goldens in `golden` (or a folder that lacks some) replace them all; frames within the
// tolerance leave the goldens as they are.
bool updated_goldens(const std::string& rendered, const std::string& golden) {
    if (!std::getenv("SHATTER_UPDATE_GOLDEN")) return false;
    try {
        const DiffSummary s = diff_paths(golden, rendered, kGoldenTolerance, "");
        if (s.failed == 0 && s.images.size() == std::size(kGoldenFrames)) return false;
    } catch (const std::exception&) {  // a missing frame or folder
    }
    fs::create_directories(golden);
    for (const auto& e : fs::directory_iterator(golden)) fs::remove(e.path());
    for (const auto& e : fs::directory_iterator(rendered)) fs::copy_file(e.path(), fs::path(golden) / e.path().filename());
    return true;
}

TEST(Golden, SmallSceneMatchesTheCommittedImages) {
    TempDir dir;
    render_golden_frames(small_render_settings(), dir.path().string());
    if (updated_goldens(dir.path().string(), golden_dir()))
        GTEST_SKIP() << "goldens re-made in " << golden_dir() << "; look at them before committing";
    const DiffSummary s = compare_with_goldens(dir.path().string());
    ASSERT_EQ(s.images.size(), std::size(kGoldenFrames));
    for (const ImageDiff& d : s.images) {
        EXPECT_TRUE(d.failures.empty()) << d.name << ": " << (d.failures.empty() ? "" : d.failures.front());
        RecordProperty(d.name + "_rmse", std::to_string(d.metrics.rmse));
    }
}

// A textured input's look is pinned as the palette's is: the v3 fixture's box with its texture
// (colours = "input") against tests/golden/textured/, at the same tolerance; drawn without its
// texture (colours = "material") it fails.
TEST(Golden, TexturedSceneMatchesTheCommittedImages) {
    TempDir dir;
    RenderSettings s = small_render_settings();
    s.colours = Colours::Input;
    render_golden_frames(s, dir.path().string(), true);
    if (updated_goldens(dir.path().string(), textured_golden_dir()))
        GTEST_SKIP() << "goldens re-made in " << textured_golden_dir() << "; look at them before committing";
    const DiffSummary d = diff_paths(textured_golden_dir(), dir.path().string(), kGoldenTolerance, "");
    ASSERT_EQ(d.images.size(), std::size(kGoldenFrames));
    for (const ImageDiff& i : d.images)
        EXPECT_TRUE(i.failures.empty()) << i.name << ": " << (i.failures.empty() ? "" : i.failures.front());
    TempDir plain;
    s.colours = Colours::Material;
    render_golden_frames(s, plain.path().string(), true);
    EXPECT_GT(diff_paths(textured_golden_dir(), plain.path().string(), kGoldenTolerance, "").failed, 0u)
        << "the box without its texture passed the textured golden comparison";
}

struct Change {
    const char* what;
    void (*apply)(RenderSettings&);
};

TEST(Golden, DeliberateChangesOfTheLookFail) {
    const Change changes[] = {
        {"key light moved 25 degrees", [](RenderSettings& s) { s.key_azimuth += 25; }},
        {"key light 15 degrees lower", [](RenderSettings& s) { s.key_elevation -= 15; }},
        {"pieces in one wrong colour", [](RenderSettings& s) { s.colours = Colours::Material; }},
        {"fracture faces untinted", [](RenderSettings& s) { s.fracture_tint = 0; }},
        {"no shadows", [](RenderSettings& s) { s.shadows = false; }},
        {"camera moved", [](RenderSettings& s) { s.camera_position = Vec3(0.5, 0.3, 0.6); }},
    };
    for (const Change& c : changes) {
        TempDir dir;
        RenderSettings s = small_render_settings();
        c.apply(s);
        render_golden_frames(s, dir.path().string());
        const DiffSummary d = compare_with_goldens(dir.path().string());
        EXPECT_GT(d.failed, 0u) << c.what << " passed the golden comparison";
    }
}

}  // namespace
}  // namespace shatter
