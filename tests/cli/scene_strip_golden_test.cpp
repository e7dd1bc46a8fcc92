// Golden strips: each built-in paper scene swept over alpha by `shatter batch` at low resolution,
// its strip compared with the committed golden by `shatter diff` at the tolerance of the render
// goldens (RMSE <= 1.5 levels, SSIM >= 0.98, at most 0.5% of pixels off by more than 24 levels).
// The strip guards the look of a whole scene: framing, colours, the props, and how far the
// pieces fly at alpha = 0 and at the sweep's largest alpha.
//
// To re-make the goldens after an intended change, run the tests with SHATTER_UPDATE_GOLDEN=1 (as
// `make refresh` does): the strips that no longer match replace their goldens; look at
// tests/golden/scenes/<scene>-strip.png, and commit them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::run_shatter;
using testing_support::TempDir;

std::string golden_of(const std::string& shot) {
    return SHATTER_SOURCE_DIR "/tests/golden/scenes/" + shot + "-strip.png";
}

// Runs the shot's sweep over alpha 0 and `alpha` with `shatter batch` in dir, at 240 x 135 for
// `duration` s, from the batch file dir/SHOT.toml; returns its strip at strip_time (unit: s), or
// an empty path, with a failure, when the batch failed.
std::string run_sweep(TempDir& dir, const std::string& shot, double alpha, double strip_time, double duration) {
    const std::string batch = dir.write(shot + ".toml", fmt::format(R"([[job]]
shot = "{}/assets/{}.toml"
set = {{ "render.width" = 240, "render.height" = 135, "render.shadow_map" = 1024, "simulate.duration" = {} }}
sweep = {{ "material.alpha" = [0, {}] }}
strip_time = {}
)", SHATTER_SOURCE_DIR, shot, duration, alpha, strip_time));
    const auto r = run_shatter({"batch", batch, "-o", dir.file("out")});
    const std::string strip = dir.file("out/" + shot + "/" + shot + ".strip.png");
    if (r.exit_code != 0 || !fs::exists(strip)) {
        ADD_FAILURE() << "shatter batch " << batch << " (exit " << r.exit_code << ")\n" << r.out << r.err;
        return "";
    }
    return strip;
}

// `shatter diff` of the strip against the golden at the render goldens' tolerance (exit 0: alike).
testing_support::CommandResult diff_strip(const std::string& golden, const std::string& strip) {
    return run_shatter({"diff", golden, strip, "--max-rmse", "1.5", "--min-ssim", "0.98", "--threshold", "24",
                        "--max-fraction", "0.005"});
}

// With SHATTER_UPDATE_GOLDEN set, a strip that no longer matches its golden (or has none) is
// copied over it, and the test says so; one within the tolerance leaves the golden as it is.
bool updated_golden(const std::string& strip, const std::string& golden) {
    if (!std::getenv("SHATTER_UPDATE_GOLDEN")) return false;
    if (fs::exists(golden) && diff_strip(golden, strip).exit_code == 0) return false;
    fs::create_directories(fs::path(golden).parent_path());
    fs::copy_file(strip, golden, fs::copy_options::overwrite_existing);
    return true;
}

TEST(SceneStrips, TheBeamSweepLooksAsCommitted) {
    TempDir dir;
    const std::string golden = golden_of("beam");
    // 0.08 s after the break, while the kicked halves still flip (by 0.4 s the block has pressed
    // them flat at every alpha).
    const std::string strip = run_sweep(dir, "beam", 1.5, 0.3, 0.35);
    ASSERT_FALSE(strip.empty());
    if (updated_golden(strip, golden)) GTEST_SKIP() << "golden re-made: " << golden << "; look at it before committing";
    auto d = diff_strip(golden, strip);
    EXPECT_EQ(d.exit_code, 0) << d.out << d.err;

    // A deliberate change of the look fails it: the alpha = 0 beam where alpha = 1.5 should be
    // (the strip is made again from the frames; every run is up to date).
    fs::copy_file(dir.file("out/beam/alpha-0/frames/frame_00009.png"),
                  dir.file("out/beam/alpha-1.5/frames/frame_00009.png"), fs::copy_options::overwrite_existing);
    ASSERT_EQ(run_shatter({"batch", dir.file("beam.toml"), "-o", dir.file("out")}).exit_code, 0);
    d = diff_strip(golden, strip);
    EXPECT_EQ(d.exit_code, 1) << d.out << d.err;
}

// The other three scenes, at the moment of their sweeps' strips (0.5 s after the first break).
struct StripCase {
    const char* shot;
    double alpha;        // the sweep's largest
    double strip_time;   // (unit: s)
};

class PaperSceneStrips : public ::testing::TestWithParam<StripCase> {};

TEST_P(PaperSceneStrips, LookAsCommitted) {
    const StripCase& c = GetParam();
    TempDir dir;
    const std::string golden = golden_of(c.shot);
    const std::string strip = run_sweep(dir, c.shot, c.alpha, c.strip_time, c.strip_time + 0.05);
    ASSERT_FALSE(strip.empty());
    if (updated_golden(strip, golden)) GTEST_SKIP() << "golden re-made: " << golden << "; look at it before committing";
    const auto d = diff_strip(golden, strip);
    EXPECT_EQ(d.exit_code, 0) << d.out << d.err;
}

INSTANTIATE_TEST_SUITE_P(Scenes, PaperSceneStrips,
                         ::testing::Values(StripCase{"chain", 2, 0.83}, StripCase{"plate", 1.5, 0.8},
                                           StripCase{"bunny_sphere", 2, 1.0}),
                         [](const ::testing::TestParamInfo<StripCase>& info) { return std::string(info.param.shot); });

}  // namespace
}  // namespace shatter
