// Golden strips: each built-in paper scene swept over alpha by `shatter batch` at low resolution,
// its strip compared with the committed golden by `shatter diff` at the tolerance of the render
// goldens (RMSE <= 1.5 levels, SSIM >= 0.98, at most 0.5% of pixels off by more than 24 levels).
// The strip guards the look of a whole scene: framing, colours, the props, and how far the
// pieces fly at alpha = 0 and at the sweep's largest alpha.
//
// To re-make the goldens after an intended change, run the tests with SHATTER_UPDATE_GOLDEN=1,
// look at tests/golden/scenes/<scene>-strip.png, and commit them.
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

const std::string kGolden = SHATTER_SOURCE_DIR "/tests/golden/scenes/beam-strip.png";

TEST(SceneStrips, TheBeamSweepLooksAsCommitted) {
    TempDir dir;
    const std::string batch = dir.write("beam.toml", R"([[job]]
shot = ")" SHATTER_SOURCE_DIR R"(/assets/beam.toml"
set = { "render.width" = 240, "render.height" = 135, "render.shadow_map" = 1024, "simulate.duration" = 0.8 }
sweep = { "material.alpha" = [0, 1.5] }
strip_time = 0.8
)");
    auto r = run_shatter({"batch", batch, "-o", dir.file("out")});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const std::string strip = dir.file("out/beam/beam.strip.png");
    ASSERT_TRUE(fs::exists(strip));
    if (std::getenv("SHATTER_UPDATE_GOLDEN")) {
        fs::create_directories(fs::path(kGolden).parent_path());
        fs::copy_file(strip, kGolden, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "golden re-made: " << kGolden << "; look at it before committing";
    }
    auto d = run_shatter({"diff", kGolden, strip, "--max-rmse", "1.5", "--min-ssim", "0.98", "--threshold", "24",
                          "--max-fraction", "0.005"});
    EXPECT_EQ(d.exit_code, 0) << d.out << d.err;

    // A deliberate change of the look fails it: the alpha = 0 beam where alpha = 1.5 should be
    // (the strip is made again from the frames; every run is up to date).
    fs::copy_file(dir.file("out/beam/alpha-0/frames/frame_00024.png"),
                  dir.file("out/beam/alpha-1.5/frames/frame_00024.png"), fs::copy_options::overwrite_existing);
    ASSERT_EQ(run_shatter({"batch", batch, "-o", dir.file("out")}).exit_code, 0);
    d = run_shatter({"diff", kGolden, strip, "--max-rmse", "1.5", "--min-ssim", "0.98", "--threshold", "24",
                     "--max-fraction", "0.005"});
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
    const std::string name = c.shot;
    const std::string golden = SHATTER_SOURCE_DIR "/tests/golden/scenes/" + name + "-strip.png";
    TempDir dir;
    const std::string batch = dir.write(name + ".toml", fmt::format(R"([[job]]
shot = "{}/assets/{}.toml"
set = {{ "render.width" = 240, "render.height" = 135, "render.shadow_map" = 1024, "simulate.duration" = {} }}
sweep = {{ "material.alpha" = [0, {}] }}
strip_time = {}
)", SHATTER_SOURCE_DIR, name, c.strip_time + 0.05, c.alpha, c.strip_time));
    auto r = run_shatter({"batch", batch, "-o", dir.file("out")});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const std::string strip = dir.file("out/" + name + "/" + name + ".strip.png");
    ASSERT_TRUE(fs::exists(strip));
    if (std::getenv("SHATTER_UPDATE_GOLDEN")) {
        fs::copy_file(strip, golden, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "golden re-made: " << golden << "; look at it before committing";
    }
    auto d = run_shatter({"diff", golden, strip, "--max-rmse", "1.5", "--min-ssim", "0.98", "--threshold", "24",
                          "--max-fraction", "0.005"});
    EXPECT_EQ(d.exit_code, 0) << d.out << d.err;
}

INSTANTIATE_TEST_SUITE_P(Scenes, PaperSceneStrips,
                         ::testing::Values(StripCase{"chain", 2, 0.83}, StripCase{"plate", 1.5, 0.8},
                                           StripCase{"bunny_sphere", 2, 1.0}),
                         [](const ::testing::TestParamInfo<StripCase>& info) { return std::string(info.param.shot); });

}  // namespace
}  // namespace shatter
