// Energy plots: a PNG of the fixed figure size from simulate's CSV, the same bytes twice, several
// runs in one plot, and bad CSVs refused with the file and line, nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "core/error.h"
#include "pipeline/energy_csv.h"
#include "pipeline/plot.h"
#include "render/png_io.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

// An energy CSV as simulate writes it (simulate/recording.cpp): a ball dropped from 1 m at
// t = 0.1 s that breaks (injecting 0.2 J) and whose kinetic energy grows as mgh falls.
std::string energy_csv(double injected) {
    std::string out = "time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J\n";
    for (int i = 0; i <= 30; ++i) {
        const double t = i / 60.0, fall = std::min(0.5 * 9.81 * t * t, 1.0);
        const double inj = t >= 0.1 ? injected : 0.0;
        out += fmt::format("{:.6f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", t, 9.81 * fall + inj, 9.81 * (1.0 - fall),
                           t < 0.1 ? 0.05 : 0.0, inj, 0.0);
    }
    return out;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void expect_bad_input(const std::string& csv_text, const std::string& expected) {
    TempDir tmp;
    const std::string csv = tmp.write("bad.energy.csv", csv_text);
    try {
        plot_energy({{"run", csv}}, "t", tmp.file("plot.png"));
        FAIL() << "no error for " << expected;
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"bad.energy.csv"});
}

TEST(Plot, OneRunGivesAFixedSizePngWithTheSameBytesTwice) {
    TempDir tmp;
    const std::string csv = tmp.write("run.energy.csv", energy_csv(0.2));
    plot_energy({{"alpha = 0.5", csv}}, "drop: energy books", tmp.file("a.png"));
    plot_energy({{"alpha = 0.5", csv}}, "drop: energy books", tmp.file("b.png"));
    const Image a = load_png(tmp.file("a.png"));
    EXPECT_EQ(a.width, 800u);  // 8 x 4.5 inches at 100 dpi
    EXPECT_EQ(a.height, 450u);
    EXPECT_EQ(slurp(tmp.file("a.png")), slurp(tmp.file("b.png")));
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"a.png", "b.png", "run.energy.csv"}));  // no temporaries
}

TEST(Plot, SeveralRunsAndHostileLabelsPlot) {
    TempDir tmp;
    const std::string a = tmp.write("a.energy.csv", energy_csv(0.1));
    const std::string b = tmp.write("b b'$(x).energy.csv", energy_csv(0.4));
    plot_energy({{"alpha = 0.5", a}, {"_$x$ \"q\" ünï αβ", b}}, "sweep $alpha", tmp.file("sweep.png"));
    const Image img = load_png(tmp.file("sweep.png"));
    EXPECT_EQ(img.width, 800u);
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x")));
}

// The books' running sums as the plot draws them: the joints' (removed + joints_damped, which at an
// iterative impact are hundreds of joules apart in opposite directions: the cat's default shot)
// and the contacts' with the step's integration; the sum of every term.
TEST(Plot, TheBooksSplitIntoWhatTheJointsTookAndWhatContactsTook) {
    const EnergySeries s = parse_energy_csv(
        "time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J,elastic_J,joint_residual,joints_damped_J,"
        "contacts_J,driven_J,integration_J\n"
        "0,0,30,0,0,0,0,0,0,0,0,0\n"
        "0.6,1.4,1.0,0,0.83,352.1,0.5,296,-349.1,24.9,0.25,0.002\n",
        "cat.energy.csv");
    ASSERT_EQ(s.joints_took.size(), 2u);
    EXPECT_NEAR(s.joints_took[1], 352.1 - 349.1, 1e-9);
    EXPECT_NEAR(s.contacts_took[1], 24.9 + 0.002, 1e-9);
    EXPECT_NEAR(s.driven[1], 0.25, 1e-12);
    // kinetic + potential + elastic + removed + joints_damped + contacts + integration - injected - driven
    EXPECT_NEAR(s.books[1], 1.4 + 1.0 + 0.5 + 352.1 - 349.1 + 24.9 + 0.002 - 0.83 - 0.25, 1e-9);
    EXPECT_NEAR(s.books[0], 30, 1e-12);
}

TEST(Plot, BadCsvIsRefusedWithFileAndLine) {
    expect_bad_input("time_s,potential_J,stored_J,injected_J\n0,1,2,3\n", "no column kinetic_J");
    expect_bad_input("time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J\n0,1,2,3,4,5\n0.1,x,2,3,4,5\n",
                     "bad.energy.csv:3: kinetic_J 'x' is not a finite number");
    expect_bad_input("time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J\n0,1,2,3\n",
                     "bad.energy.csv:2: 4 fields where the header has 6");
    expect_bad_input("time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J\n0,nan,2,3,4,5\n", "not a finite");
    expect_bad_input("time_s,kinetic_J,potential_J,stored_J,injected_J,removed_J\n", "no samples");
    expect_bad_input("", "empty energy CSV");
}

TEST(Plot, MissingCsvIsBadInput) {
    TempDir tmp;
    EXPECT_THROW(plot_energy({{"run", tmp.file("none.csv")}}, "t", tmp.file("p.png")), Error);
    EXPECT_TRUE(tmp.entries().empty());
}

}  // namespace
}  // namespace shatter
