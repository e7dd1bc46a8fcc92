// `shatter run` reports simulate's instability guard ([simulate] on_instability,
// docs/reliability.md) in summary.json and in its closing summary: how many steps were clamped and
// where the first clamp was, or where an unstable run stopped; the record comes from
// NAME.instability.json, so a re-run with simulate up to date says the same.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/instability_record.h"
#include "pipeline/run.h"
#include "simulate/simulate.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using testing_support::TempDir;

// The runaway scene of tests/simulate/instability_test.cpp as a shot: a 4 x 4 plate of 5 cm
// boxes spinning at 100 rad/s, joints so soft that they need CFM 0.95 at this step (max_cfm
// raised to 0.99 to allow it), one solver iteration per step of the iterative joints: the solver
// feeds energy in and the kinetic energy passes the guard's limit at t = 2/30 s.
constexpr const char* kWildShot = R"([generate]
kind = "plate"
count = 4
size = [0.05, 0.05, 0.05]
density = 2400
[object]
position = [0, 0.3, 0]
rotation = [20, 0, 10]
angular_velocity = [100, 30, 0]
[material]
stiffness = 1.2e5
strength = 1e12
alpha = 1
[simulate]
duration = 0.5
fps = 30
substeps = 1
iterations = 1
joints = "iterative"
max_cfm = 0.99
)";

RunResult run_wild(const TempDir& dir, std::vector<std::string> overrides) {
    RunOptions o;
    o.shot = dir.write("wild.toml", kWildShot);
    o.overrides = std::move(overrides);
    o.output_dir = dir.file("out");
    o.stages = {Stage::Prescore, Stage::Simulate};  // summary.json needs no frames
    o.progress = false;
    return run_shot(o);
}

// The "stability:" lines of a closing summary.
std::string stability_lines(const std::string& closing) {
    std::string out;
    for (size_t at = closing.find("stability:"); at != std::string::npos; at = closing.find("stability:", at + 1))
        out += closing.substr(at, closing.find('\n', at) - at + 1);
    return out;
}

json summary_file(const TempDir& dir) { return json::parse(read_file(dir.file("out/summary.json"), "summary")); }

TEST(RunInstability, AStoppedRunSaysWhenWhichPieceAndWhichConstraintInSummaryJson) {
    TempDir dir;
    const RunResult r = run_wild(dir, {});
    EXPECT_EQ(r.exit_code, static_cast<int>(ExitCode::Unstable));
    ASSERT_FALSE(r.summary.empty());
    EXPECT_EQ(summary_file(dir), r.summary);
    EXPECT_FALSE(r.summary["simulation"]["complete"].get<bool>());
    const json& i = r.summary["instability"];
    EXPECT_EQ(i["on_instability"], "stop");
    EXPECT_EQ(i["clamps"], 0);
    EXPECT_TRUE(i["first_clamp"].is_null());
    const json& stop = i["stopped"];
    ASSERT_TRUE(stop.is_object()) << i.dump(2);
    EXPECT_NEAR(stop["time_s"].get<double>(), 2.0 / 30, 1e-9);  // from the simulation, not the message
    ASSERT_TRUE(stop["piece"].is_number_unsigned()) << stop.dump(2);
    EXPECT_LT(stop["piece"].get<uint64_t>(), 16u);
    ASSERT_TRUE(stop["constraint"].is_number_unsigned()) << stop.dump(2);
    EXPECT_LT(stop["constraint"].get<uint64_t>(), r.summary["model"]["constraints"].get<uint64_t>());
    EXPECT_TRUE(stop["last_broken_constraint"].is_null());  // strength 1e12: nothing broke
    const std::string what = stop["what"].get<std::string>();
    EXPECT_NE(what.find("exceeds what the scene can supply"), std::string::npos) << what;
    // The numbers are the ones the message names too.
    EXPECT_NE(what.find("piece " + std::to_string(stop["piece"].get<uint64_t>()) + " is the fastest"), std::string::npos)
        << what;
    EXPECT_NE(what.find("constraint " + std::to_string(stop["constraint"].get<uint64_t>()) + " (pieces "),
              std::string::npos)
        << what;
    EXPECT_EQ(r.summary["files"]["instability.json"], "wild.instability.json");

    const std::string closing = format_run_summary(r);
    EXPECT_NE(closing.find("stability: STOPPED at t = 0.0667 s, piece " + std::to_string(stop["piece"].get<uint64_t>()) +
                           ", constraint " + std::to_string(stop["constraint"].get<uint64_t>())),
              std::string::npos)
        << closing;
}

TEST(RunInstability, ClampCountsTheClampsAndTheFirstAndARerunSaysTheSame) {
    TempDir dir;
    const RunResult r = run_wild(dir, {"simulate.on_instability=clamp"});
    ASSERT_EQ(r.exit_code, 0);
    EXPECT_TRUE(r.summary["simulation"]["complete"].get<bool>());
    const json& i = r.summary["instability"];
    EXPECT_EQ(i["on_instability"], "clamp");
    EXPECT_GT(i["clamps"].get<uint64_t>(), 0u);
    EXPECT_TRUE(i["stopped"].is_null());
    const json& first = i["first_clamp"];
    ASSERT_TRUE(first.is_object()) << i.dump(2);
    EXPECT_NEAR(first["time_s"].get<double>(), 2.0 / 30, 1e-9);  // exact: from the simulation, not the message
    EXPECT_TRUE(first["piece"].is_number_unsigned()) << first.dump(2);
    EXPECT_TRUE(first["constraint"].is_number_unsigned()) << first.dump(2);
    EXPECT_NE(first["what"].get<std::string>().find("kinetic energy"), std::string::npos);
    const std::string closing = format_run_summary(r);
    const uint64_t n = i["clamps"].get<uint64_t>();
    EXPECT_NE(closing.find("stability: velocities clamped in " + std::to_string(n) + (n == 1 ? " step" : " steps") +
                           " (on_instability = clamp), the first at t = 0.0667 s, piece " +
                           std::to_string(first["piece"].get<uint64_t>()) + ", constraint " +
                           std::to_string(first["constraint"].get<uint64_t>())),
              std::string::npos)
        << closing;
    EXPECT_EQ(closing.find("STOPPED"), std::string::npos) << closing;

    // simulate is up to date now: the record is read back from wild.instability.json.
    const std::string bytes = read_file(dir.file("out/summary.json"), "summary");
    const RunResult again = run_wild(dir, {"simulate.on_instability=clamp"});
    ASSERT_EQ(again.stages.at(1).stage, Stage::Simulate);
    EXPECT_EQ(again.stages[1].outcome, StageOutcome::UpToDate);
    EXPECT_EQ(read_file(dir.file("out/summary.json"), "summary"), bytes);
    EXPECT_EQ(stability_lines(format_run_summary(again)), stability_lines(closing));
}

TEST(RunInstability, AStableRunRecordsNoClampAndNoStop) {
    TempDir dir;
    // The same plate not spinning: nothing to clamp.
    const RunResult r = run_wild(dir, {"simulate.on_instability=clamp", "object.angular_velocity=[0, 0, 0]"});
    ASSERT_EQ(r.exit_code, 0);
    const json& i = r.summary["instability"];
    EXPECT_EQ(i["clamps"], 0);
    EXPECT_TRUE(i["first_clamp"].is_null());
    EXPECT_TRUE(i["stopped"].is_null());
    EXPECT_NE(format_run_summary(r).find("stability: no clamp was needed (on_instability = clamp)"), std::string::npos);

    TempDir plain;
    const RunResult s = run_wild(plain, {"object.angular_velocity=[0, 0, 0]"});
    ASSERT_EQ(s.exit_code, 0);
    EXPECT_EQ(s.summary["instability"]["on_instability"], "stop");
    EXPECT_EQ(format_run_summary(s).find("stability:"), std::string::npos);  // nothing to say
}

// A stage is current only when its stamp holds the key and every output it makes is there: a
// folder whose simulate stamp does not list NAME.instability.json, and which lacks the file, runs
// simulate again rather than leave summary.json without the record.
TEST(RunInstability, AFolderWithoutTheRecordRunsSimulateAgain) {
    TempDir dir;
    ASSERT_EQ(run_wild(dir, {"simulate.on_instability=clamp"}).exit_code, 0);
    const std::string stamp_path = dir.file("out/.shatter/simulate.json");
    json stamp = json::parse(read_file(stamp_path, "stamp"));
    ASSERT_TRUE(stamp["files"].contains("wild.instability.json")) << stamp.dump(2);
    stamp["files"].erase("wild.instability.json");
    write_file_atomic(stamp_path, stamp.dump(2) + "\n");
    fs::remove(dir.file("out/wild.instability.json"));
    fs::remove(dir.file("out/summary.json"));

    const RunResult again = run_wild(dir, {"simulate.on_instability=clamp"});
    ASSERT_EQ(again.exit_code, 0);
    ASSERT_EQ(again.stages.at(1).stage, Stage::Simulate);
    EXPECT_EQ(again.stages[1].outcome, StageOutcome::Ran);
    EXPECT_TRUE(fs::exists(dir.file("out/wild.instability.json")));
    EXPECT_GT(again.summary["instability"]["clamps"].get<uint64_t>(), 0u);
}

// A NaN after breaks: the guard names the first non-finite piece, the constraint broken last and
// the one with the largest load (simulate/instability.cpp, InstabilityGuard::where).
TEST(RunInstability, TheRecordTakesTheTimePieceAndConstraintsFromTheGuard) {
    SimulationResult sim;
    sim.complete = false;
    sim.stop_reason = "at t = 1.2340 s a piece's position or velocity became NaN or infinite: piece 3 is the first "
                      "whose position or velocity is not finite; constraint 12 (pieces 3 and 4) broke last, at t = "
                      "1.2000 s; constraint 7 (pieces 1 and 2) carries the largest load, 5 N (0.5 of its strength)";
    sim.stopped_at = {1.234, 3, 7, 12};
    const json r = instability_record(InstabilityMode::Stop, sim);
    EXPECT_EQ(r["on_instability"], "stop");
    EXPECT_EQ(r["clamps"], 0);
    EXPECT_TRUE(r["first_clamp"].is_null());
    const json& e = r["stopped"];
    EXPECT_DOUBLE_EQ(e["time_s"].get<double>(), 1.234);
    EXPECT_EQ(e["piece"], 3);
    EXPECT_EQ(e["constraint"], 7);
    EXPECT_EQ(e["last_broken_constraint"], 12);
    EXPECT_EQ(e["what"], sim.stop_reason);
    EXPECT_EQ(format_instability(r), "stability: STOPPED at t = 1.2340 s, piece 3, constraint 7 (the full message: "
                                     "run.log, summary.json: instability)\n");
    // A guard that names nothing still gives a record.
    sim.stopped_at = {};
    const json bare = instability_record(InstabilityMode::Stop, sim)["stopped"];
    EXPECT_TRUE(bare["time_s"].is_null() && bare["piece"].is_null() && bare["constraint"].is_null()) << bare.dump();
}

TEST(RunInstability, ADamagedRecordIsBadInputNamingTheFile) {
    const json good = json::parse(R"({"on_instability": "clamp", "clamps": 1, "first_clamp": {"time_s": 0.1,
        "piece": 2, "constraint": null, "last_broken_constraint": null, "what": "at t = 0.1000 s ..."}, "stopped": null})");
    EXPECT_EQ(parse_instability_record(good.dump(), "x.instability.json"), good);
    EXPECT_EQ(instability_where(good["first_clamp"]), "at t = 0.1000 s, piece 2");
    for (const char* bad : {"", "{", "[]", R"({"on_instability": "clamp"})",
                            R"({"on_instability": "clamp", "clamps": 1, "first_clamp": null, "stopped": null})",
                            R"({"on_instability": "stop", "clamps": -1, "first_clamp": null, "stopped": null})",
                            R"({"on_instability": "stop", "clamps": 0, "first_clamp": null, "stopped": {"what": 3}})"}) {
        try {
            parse_instability_record(bad, "x.instability.json");
            ADD_FAILURE() << "accepted: " << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::BadInput) << bad;
            EXPECT_NE(std::string(e.what()).find("x.instability.json: not an instability record"), std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
}  // namespace shatter
