// Golden strips: the built-in beam scene swept over alpha by `shatter batch` at low resolution,
// its strip compared with the committed golden by `shatter diff` at the tolerance of the render
// goldens (RMSE <= 1.5 levels, SSIM >= 0.98, at most 0.5% of pixels off by more than 24 levels).
// The strip guards the look of a whole scene: framing, colours, the goal posts and the block,
// and how far the broken half flies at each alpha.
//
// To re-make the golden after an intended change, run the test with SHATTER_UPDATE_GOLDEN=1,
// look at tests/golden/scenes/beam-strip.png, and commit it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

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

}  // namespace
}  // namespace shatter
