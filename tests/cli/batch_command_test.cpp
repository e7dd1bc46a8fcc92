// `shatter batch`: a sweep runs in parallel workers sharing one prescore, a bad job fails alone,
// and the sweep's strip, energy plot and table are made.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include "support/cube_shot.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::run_shatter;
using testing_support::slurp;
using testing_support::TempDir;
using testing_support::kCubeSweepBatch;

// A PNG's width and height from its IHDR chunk (bytes 16 to 23, big-endian).
std::optional<std::pair<uint32_t, uint32_t>> read_png_size(const std::string& path) {
    const std::string b = slurp(path);
    if (b.size() < 24 || b.compare(1, 3, "PNG") != 0) return std::nullopt;
    auto be32 = [&](size_t i) {
        return uint32_t(uint8_t(b[i])) << 24 | uint32_t(uint8_t(b[i + 1])) << 16 | uint32_t(uint8_t(b[i + 2])) << 8 |
               uint32_t(uint8_t(b[i + 3]));
    };
    return std::make_pair(be32(16), be32(20));
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

TEST(BatchCommand, SweepSharesOnePrescoreIsolatesABadJobAndMakesTheStripPlotAndTable) {
    TempDir dir;
    testing_support::write_cube_shot(dir);
    const std::string batch = dir.write("sweep.toml", kCubeSweepBatch);
    const std::string out = dir.file("out");
    auto r = run_shatter({"batch", batch, "-o", out});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // one job failed
    EXPECT_NE(r.out.find("cube/alpha-0 "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("cube/alpha-2 "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bad/run"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("render.width = 100000 is outside"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("1 of 3 runs FAILED"), std::string::npos) << r.out;

    // Both alpha runs finished, and only one of them tetrahedralized.
    std::string logs;
    for (const char* run : {"alpha-0", "alpha-2"}) {
        const fs::path d = fs::path(out) / "cube" / run;
        EXPECT_TRUE(fs::exists(d / "cube.mp4")) << run;
        EXPECT_TRUE(slurp((d / "cube.model").string()) == slurp((fs::path(out) / "cube/alpha-0/cube.model").string()));
        logs += slurp((d / "run.log").string());
    }
    EXPECT_EQ(count(logs, "prescore: ran"), 1u) << logs;
    EXPECT_EQ(count(logs, "prescore: from cache"), 1u) << logs;
    EXPECT_EQ(count(logs, "simulate: ran"), 2u) << logs;

    // The sweep's outputs: a strip of two panels side by side, the plot, the table.
    const auto strip = read_png_size((fs::path(out) / "cube/cube.strip.png").string());
    ASSERT_TRUE(strip.has_value());
    EXPECT_GE(strip->first, 2u * 480u);  // two 480-pixel panels and the gaps around them
    EXPECT_LT(strip->first, 2u * 480u + 64u);
    EXPECT_TRUE(fs::exists(fs::path(out) / "cube/cube.energy.png"));
    const std::string table = slurp((fs::path(out) / "cube/cube.table.md").string());
    EXPECT_NE(table.find("| alpha = 0 |"), std::string::npos) << table;
    EXPECT_NE(table.find("| alpha = 2 |"), std::string::npos) << table;

    // Run again: everything is up to date, and the bad job still fails alone.
    auto again = run_shatter({"batch", batch, "-o", out});
    EXPECT_EQ(again.exit_code, 1);
    EXPECT_EQ(count(slurp(out + "/cube/alpha-2/run.log"), "simulate: up to date"), 1u);
}

// Mesh files given by name, the way a folder of meshes is fractured (`shatter batch meshes/*.obj`):
// each runs the default shot into a job named by its file (the second file of the same name gets
// its extension), with the --set overrides in every run; index.html has a row per run. A bad
// --set is refused before anything is written; so is a file that is not there.
TEST(BatchCommand, MeshesGivenByNameEachRunTheDefaultShotWithTheSets) {
    TempDir dir;
    fs::create_directories(dir.file("a"));
    fs::create_directories(dir.file("b"));
    fs::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", dir.file("a/cube.obj"));
    fs::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", dir.file("b/cube.obj"));
    const std::string out = dir.file("out");
    const std::vector<std::string> sets = {"--set", "render.width=160", "--set", "render.height=90",
                                           "--set", "render.shadow_map=512", "--set", "simulate.duration=0.5",
                                           "--set", "prescore.pieces=4"};
    std::vector<std::string> args = {"batch", dir.file("a/cube.obj"), dir.file("b/cube.obj"), "-o", out};
    args.insert(args.end(), sets.begin(), sets.end());
    auto r = run_shatter(args);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("all 2 runs succeeded"), std::string::npos) << r.out;
    for (const char* job : {"cube", "cube-obj"}) {
        const fs::path run = fs::path(out) / job / "run";
        EXPECT_TRUE(fs::exists(run / "cube.mp4")) << job;
        const auto frame = read_png_size((run / "frames" / "frame_00000.png").string());
        ASSERT_TRUE(frame.has_value()) << job;
        EXPECT_EQ(*frame, std::make_pair(160u, 90u)) << job;
        EXPECT_NE(slurp((run / "summary.json").string()).find("\"pieces\": 4"), std::string::npos) << job;
    }
    // The same mesh, the same default shot, the same model.
    EXPECT_EQ(slurp(out + "/cube/run/cube.model"), slurp(out + "/cube-obj/run/cube.model"));
    const std::string index = slurp(out + "/index.html");
    EXPECT_NE(index.find("cube-obj"), std::string::npos);

    const std::string fresh = dir.file("out2");
    r = run_shatter({"batch", dir.file("a/cube.obj"), "-o", fresh, "--set", "render.width=abc"});
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("--set render.width=abc"), std::string::npos) << r.err;
    r = run_shatter({"batch", dir.file("a/cube.obj"), dir.file("a/nope.obj"), "-o", fresh});
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("nope.obj: no such file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(fresh));
}

TEST(BatchCommand, AMalformedBatchFileIsRefusedWithItsLine) {
    TempDir dir;
    const std::string batch = dir.write("b.toml", "[[job]]\nshot = \"x.toml\"\nsweep = { \"material.alpha\" = [] }\n");
    auto r = run_shatter({"batch", batch});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("b.toml:3"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("non-empty array"), std::string::npos) << r.err;
    const std::string typo = dir.write("c.toml", "[[job]]\nshot = \"x.toml\"\nsweeps = { \"material.alpha\" = [1] }\n");
    r = run_shatter({"batch", typo});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("c.toml:3"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean 'sweep'"), std::string::npos) << r.err;
    const std::string none = dir.write("d.toml", "[batch]\nworkers = 2\n");
    r = run_shatter({"batch", none});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("at least one [[job]]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace shatter
