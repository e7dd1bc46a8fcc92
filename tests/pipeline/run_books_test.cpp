// `shatter run` closes with the energy books: stored, alpha x stored, injected and their ratio.
// The paper's beam (assets/beam.toml) solves its kicks for exact energy (exact_energy = true), so
// what its breaks inject is alpha x what they stored: the ratio reads 1.000. With the automatic
// step its two joints in tension break and it hangs on the two in compression (docs/physics.md
// section 7): one fragment, said in the singular. The energy line names the plot of those books,
// a file the run made.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "pipeline/run.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

TEST(RunBooks, TheClosingSummaryPrintsTheBooksAndTheirRatio) {
    TempDir dir;
    RunOptions o;
    o.shot = SHATTER_SOURCE_DIR "/assets/beam.toml";
    o.output_dir = dir.file("out");
    o.stages = {Stage::Prescore, Stage::Simulate, Stage::Plot};
    o.progress = false;
    const RunResult r = run_shot(o);
    ASSERT_EQ(r.exit_code, 0);
    ASSERT_GT(r.summary["simulation"]["breaks"].get<size_t>(), 0u);
    const std::string closing = format_run_summary(r);
    const size_t at = closing.find("books:    stored ");
    ASSERT_NE(at, std::string::npos) << closing;
    const std::string line = closing.substr(at, closing.find('\n', at) - at);
    EXPECT_NE(line.find("x alpha 1 = "), std::string::npos) << line;
    EXPECT_NE(line.find("(1.000 x alpha x stored)"), std::string::npos) << line;
    EXPECT_NE(closing.find("fracture: 4 breaks -> 2 fragments; "), std::string::npos) << closing;
    const size_t energy = closing.find("energy:   ");
    ASSERT_NE(energy, std::string::npos) << closing;
    const std::string energy_line = closing.substr(energy, closing.find('\n', energy) - energy);
    const size_t open = energy_line.rfind(" ("), close = energy_line.rfind(')');
    ASSERT_TRUE(open != std::string::npos && close == energy_line.size() - 1) << energy_line;
    const std::string plot = energy_line.substr(open + 2, close - open - 2);
    EXPECT_EQ(plot, r.output_dir + "/" + r.summary["files"]["energy.png"].get<std::string>()) << energy_line;
    EXPECT_TRUE(std::filesystem::is_regular_file(plot)) << plot;
}

}  // namespace
}  // namespace shatter
