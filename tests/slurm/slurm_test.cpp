// `shatter submit --slurm` against a real single-node Slurm cluster (slurmctld, slurmd and munged
// on loopback, scripts/slurm-local.sh; ctest starts it before these tests and stops it after).
// A test skips, naming the reason, when the cluster cannot be started here (not root, no Slurm).
//
// What they prove: frames made by the job chain are byte for byte those of a local `shatter run`,
// with shot and output paths full of shell syntax, quotes, a newline and non-ASCII letters (and no
// command in them ever runs); a failed array task is named with its frames and log and makes
// `submit --wait` exit 1; jobs still queued from an earlier submit are reused, and a resubmission
// after a failure does not run prescore and simulate again.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "pipeline/process.h"
#include "pipeline/slurm.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::run_shatter;
using testing_support::slurp;
using testing_support::TempDir;

// A two-piece glass beam pushed by a block: no mesh, no CGAL, a second of work per stage.
// 0.5 s at 30 fps = 16 frames of 160 x 90.
constexpr const char* kShot = R"([generate]
kind = "beam"
count = 2
size = [0.3, 0.03, 0.03]
constraints_per_side = 2
density = 2500

[[scene.kinematic]]
name = "block"
size = [0.08, 0.06, 0.06]
position = [0, 0.032, 0.05]
velocity = [0, 0, -0.4]

[material]
stiffness = 5.25e11
strength = 2.31e7
alpha = 1.0

[simulate]
duration = 0.5
fps = 30

[render]
width = 160
height = 90
camera_position = [0.0, 0.7, 0.9]
camera_target = [0, 0.0, -0.1]
fov = 40
)";
constexpr uint32_t kFrames = 16;

// Every shell metacharacter we could think of, a newline, a '%' (Slurm's --output patterns) and
// non-ASCII letters. A command in it that ran would leave a file named PWNED behind.
const std::string kHostile = "sp ace 'q' \"dq\" $(touch PWNED) `touch PWNED2`; touch PWNED3 & é ü 雪\nnl %j 100%";

// Starts the local cluster (idempotent) and points the Slurm clients at it; the reason when it
// cannot run here.
std::optional<std::string> cluster_unavailable() {
    const std::string script = std::string(SHATTER_SOURCE_DIR) + "/scripts/slurm-local.sh";
    const ProcessResult r = run_process({"/bin/bash", script, "start"});
    if (r.exit_code == 77) return last_lines(r.err, 3);
    if (!r.ok()) return "scripts/slurm-local.sh start failed: " + r.describe() + ": " + last_lines(r.err, 5);
    // It prints "export SLURM_CONF=PATH" (a path under /tmp without characters to quote).
    const std::string line = last_lines(r.out, 1), prefix = "export SLURM_CONF=";
    if (line.rfind(prefix, 0) != 0) return "scripts/slurm-local.sh start printed no SLURM_CONF: " + r.out;
    ::setenv("SLURM_CONF", line.substr(prefix.size()).c_str(), 1);
    return std::nullopt;
}

#define REQUIRE_CLUSTER()                                                    \
    do {                                                                     \
        if (auto why = cluster_unavailable()) GTEST_SKIP() << *why;          \
    } while (0)

std::string frame_name(uint32_t f) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%05u.png", f);
    return buf;
}

// No file named PWNED* anywhere under `root`.
void expect_nothing_ran(const fs::path& root) {
    for (const auto& e : fs::recursive_directory_iterator(root))
        EXPECT_EQ(e.path().filename().string().rfind("PWNED", 0), std::string::npos) << e.path();
}

nlohmann::json jobs_of(const fs::path& out) { return nlohmann::json::parse(slurp((out / "slurm" / "jobs.json").string())); }

std::string job_id(const nlohmann::json& jobs, const std::string& kind) {
    for (const auto& j : jobs["jobs"])
        if (j["kind"] == kind) return j["id"].get<std::string>();
    return "";
}

ProcessResult slurm_client(const std::vector<std::string>& argv) {
    std::vector<std::string> a = argv;
    a[0] = find_program(a[0]).value_or(a[0]);
    return run_process(a);
}

TEST(Submit, FramesFromSlurmEqualALocalRunWithHostilePaths) {
    REQUIRE_CLUSTER();
    TempDir tmp;
    const fs::path dir = tmp.path() / kHostile;
    fs::create_directories(dir);
    const std::string shot = (dir / "beam ;`x` $(y) é.toml").string();
    std::ofstream(shot) << kShot;
    const fs::path local = tmp.path() / "local", slurm = dir / "out $(touch PWNED4) ;é";
    const std::vector<std::string> set = {"--set", "simulate.substeps=8", "--set", "render.fov=40"};

    std::vector<std::string> run_args = {"run", shot, "-o", local.string(), "--no-progress"};
    run_args.insert(run_args.end(), set.begin(), set.end());
    const auto local_run = run_shatter(run_args, tmp.path().string());
    ASSERT_EQ(local_run.exit_code, 0) << local_run.err;

    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> submit = {"submit", shot, "--slurm", "-o", slurm.string(), "--chunks", "3", "--wait"};
    submit.insert(submit.end(), set.begin(), set.end());
    const auto r = run_shatter(submit, tmp.path().string());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    std::printf("submit --wait: %.1f s for 3 jobs (5 with the array's tasks)\n", seconds);
    EXPECT_NE(r.out.find("all 3 jobs succeeded"), std::string::npos) << r.out;

    for (uint32_t f = 0; f < kFrames; ++f) {
        const std::string a = slurp((local / "frames" / frame_name(f)).string());
        const std::string b = slurp((slurm / "frames" / frame_name(f)).string());
        ASSERT_FALSE(a.empty()) << frame_name(f);
        EXPECT_TRUE(a == b) << frame_name(f) << " differs between the local run and the Slurm jobs";
    }
    EXPECT_FALSE(fs::exists(slurm / "frames" / frame_name(kFrames)));
    const std::string name = fs::path(shot).stem().string();
    for (const std::string& file : std::vector<std::string>{name + ".model", name + ".traj", name + ".breaks.jsonl", "summary.json"})
        EXPECT_TRUE(slurp((local / file).string()) == slurp((slurm / file).string())) << file;
    for (const std::string& file : std::vector<std::string>{name + ".mp4", name + ".contact.png", name + ".energy.png", name + ".glb"})
        EXPECT_TRUE(fs::exists(slurm / file)) << file;
    const auto summary = nlohmann::json::parse(slurp((slurm / "summary.json").string()));
    EXPECT_EQ(summary["shot"], shot);
    EXPECT_EQ(summary["simulation"]["frames"], kFrames);

    // Three jobs, the render array with three tasks, each with its log.
    const auto jobs = jobs_of(slurm);
    ASSERT_EQ(jobs["jobs"].size(), 3u);
    const std::string render = job_id(jobs, "render");
    for (int t = 0; t < 3; ++t)
        EXPECT_TRUE(fs::exists(slurm / "slurm" / ("render-" + render + "_" + std::to_string(t) + ".log"))) << t;
    EXPECT_TRUE(fs::exists(slurm / "slurm" / ("simulate-" + job_id(jobs, "simulate") + ".log")));
    EXPECT_TRUE(fs::exists(slurm / "slurm" / ("finish-" + job_id(jobs, "finish") + ".log")));
    expect_nothing_ran(tmp.path());
}

TEST(Submit, FailedTaskIsNamedAndResubmissionReusesFinishedStages) {
    REQUIRE_CLUSTER();
    TempDir tmp;
    const std::string shot = tmp.write("beam.toml", kShot);
    const fs::path out = tmp.path() / "out é";
    const std::vector<std::string> submit = {"submit", shot, "--slurm", "-o", out.string(), "--chunks", "3"};

    // Submitted held; render task 1 is cancelled before it can start.
    auto held = submit;
    held.push_back("--sbatch-arg=--hold");
    const auto first = run_shatter(held);
    ASSERT_EQ(first.exit_code, 0) << first.out << first.err;
    const auto jobs = jobs_of(out);
    const std::string sim = job_id(jobs, "simulate"), render = job_id(jobs, "render"), finish = job_id(jobs, "finish");
    ASSERT_FALSE(sim.empty() || render.empty() || finish.empty()) << jobs.dump();
    ASSERT_TRUE(slurm_client({"scancel", render + "_1"}).ok());

    // Submitting again while they are queued waits for them instead of submitting new ones; they
    // are released once that submit has recorded them as reused.
    auto wait = submit;
    wait.push_back("--wait");
    std::vector<std::string> argv = wait;
    argv.insert(argv.begin(), SHATTER_BINARY);
    ChildProcess waiting(argv, {});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!jobs_of(out)["jobs"][0].value("reused", false)) {
        ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the second submit did not record its jobs";
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    EXPECT_EQ(job_id(jobs_of(out), "simulate"), sim);
    EXPECT_EQ(job_id(jobs_of(out), "render"), render);
    ASSERT_TRUE(slurm_client({"scontrol", "release", sim, render, finish}).ok());
    const ProcessResult failed = waiting.wait();
    EXPECT_EQ(failed.exit_code, 1) << failed.out << failed.err;
    EXPECT_NE(failed.out.find("earlier submit"), std::string::npos) << failed.out;
    const std::string named = "render task 1 of job " + render + " (frames 5..9) failed";
    EXPECT_NE(failed.err.find(named), std::string::npos) << failed.err;
    EXPECT_NE(failed.err.find(out.string() + "/slurm/render-" + render + "_1.log"), std::string::npos) << failed.err;
    EXPECT_NE(failed.err.find("did not run"), std::string::npos) << failed.err;  // the finish job
    EXPECT_FALSE(fs::exists(out / "frames" / frame_name(7)));

    // After the failure: prescore and simulate are up to date and get no job; the rest completes.
    const auto again = run_shatter(wait);
    ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
    EXPECT_NE(again.out.find("prescore, simulate up to date"), std::string::npos) << again.out;
    const auto resubmitted = jobs_of(out);
    EXPECT_EQ(job_id(resubmitted, "simulate"), "") << resubmitted.dump();
    EXPECT_EQ(resubmitted["jobs"].size(), 2u);
    for (uint32_t f = 0; f < kFrames; ++f) EXPECT_TRUE(fs::exists(out / "frames" / frame_name(f))) << f;
    EXPECT_TRUE(fs::exists(out / "summary.json"));
}

TEST(Submit, JobFailureReportsItsExitCodeAndLog) {
    REQUIRE_CLUSTER();
    TempDir tmp;
    const std::string shot = tmp.write("beam.toml", kShot);
    const fs::path out = tmp.path() / "out";
    // Held while we take the shot away: the prescore/simulate job then fails as bad input (exit 3).
    ChildProcess submit({SHATTER_BINARY, "submit", shot, "--slurm", "-o", out.string(), "--chunks", "2", "--wait",
                         "--sbatch-arg=--hold"},
                        {});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!fs::exists(out / "slurm" / "jobs.json") || jobs_of(out)["jobs"].size() < 3) {
        ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "submit did not record its jobs";
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const auto jobs = jobs_of(out);
    fs::remove(shot);
    ASSERT_TRUE(slurm_client({"scontrol", "release", job_id(jobs, "simulate"), job_id(jobs, "render"),
                              job_id(jobs, "finish")}).ok());
    const ProcessResult r = submit.wait();
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    const std::string sim = job_id(jobs, "simulate");
    EXPECT_NE(r.err.find("prescore/simulate job " + sim + " failed: exit code 3; log: " + out.string() +
                         "/slurm/simulate-" + sim + ".log"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("beam.toml"), std::string::npos) << "the log's last lines name the problem: " << r.err;
    EXPECT_NE(r.err.find("render task 1 of job " + job_id(jobs, "render") + " (frames 8..15) did not run"),
              std::string::npos) << r.err;
}

TEST(Submit, BatchFileRunsEverySweepRunThenTheSweepJob) {
    REQUIRE_CLUSTER();
    TempDir tmp;
    tmp.write("beam.toml", kShot);
    const std::string jobs = tmp.write("sweep.toml", "[batch]\noutput = \"swept\"\n\n[[job]]\nshot = \"beam.toml\"\n"
                                                     "sweep = { \"material.alpha\" = [0.5, 1] }\n");
    const auto r = run_shatter({"submit", jobs, "--slurm", "--chunks", "1", "--wait"}, tmp.path().string());
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("all 7 jobs succeeded"), std::string::npos) << r.out;  // 2 x 3 + the sweep job
    const fs::path out = tmp.path() / "swept";
    for (const char* run : {"alpha-0.5", "alpha-1"}) {
        EXPECT_TRUE(fs::exists(out / "beam" / run / "summary.json")) << run;
        EXPECT_TRUE(fs::exists(out / "beam" / run / "frames" / frame_name(kFrames - 1))) << run;
    }
    for (const char* file : {"beam.table.md", "beam.table.csv", "beam.energy.png", "beam.strip.png"})
        EXPECT_TRUE(fs::exists(out / "beam" / file)) << file;
}

// Several shots given by name, as `shatter batch` takes them: a job of one run each (the second
// file of the same name gets its extension), --set in every run and in the final batch job, which
// makes the index page.
TEST(Submit, FilesGivenByNameRunAsABatchWithTheirSets) {
    REQUIRE_CLUSTER();
    TempDir tmp;
    tmp.write("beam.toml", kShot);
    fs::create_directories(tmp.path() / "other");
    tmp.write("other/beam.toml", kShot);
    const auto r = run_shatter({"submit", "beam.toml", "other/beam.toml", "--set", "material.alpha=0.5", "--slurm",
                                "--chunks", "1", "-o", "many", "--wait"},
                               tmp.path().string());
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("all 7 jobs succeeded"), std::string::npos) << r.out;  // 2 x 3 + the batch job
    const fs::path out = tmp.path() / "many";
    for (const char* job : {"beam", "beam-toml"}) {
        const fs::path run = out / job / "run";
        ASSERT_TRUE(fs::exists(run / "summary.json")) << job;
        EXPECT_EQ(nlohmann::json::parse(slurp((run / "summary.json").string()))["alpha"], 0.5) << job;
        EXPECT_TRUE(fs::exists(run / "frames" / frame_name(kFrames - 1))) << job;
    }
    EXPECT_TRUE(fs::exists(out / "index.html"));
}

// squeue's records as `submit --wait` reads them (the format of query_jobs; no cluster needed).
TEST(Squeue, RecordsGiveTasksPendingRangesAndExitCodes) {
    const auto jobs = parse_squeue("12|12|N/A|CANCELLED|0|DependencyNeverSatisfied|\n"
                                   "9|9|0-3,6%2|PENDING|0|Dependency|\n"
                                   "14|9|5|FAILED|768|NonZeroExitCode|\n"
                                   "15|9|4|FAILED|9|NonZeroExitCode|\n"
                                   "16|9|7|COMPLETED|0|None|\n");
    ASSERT_EQ(jobs.size(), 5u);
    EXPECT_EQ(jobs[0].job_id, "12");
    EXPECT_FALSE(jobs[0].task);
    EXPECT_TRUE(jobs[0].finished());
    EXPECT_EQ(jobs[0].describe(), "cancelled: a job it waits for failed");
    EXPECT_EQ(jobs[1].pending, (std::vector<uint32_t>{0, 1, 2, 3, 6}));
    EXPECT_FALSE(jobs[1].finished());
    EXPECT_EQ(jobs[2].job_id, "9");  // a task is known by its array's id
    EXPECT_EQ(jobs[2].task, 5u);
    EXPECT_EQ(jobs[2].describe(), "exit code 3");  // 768 is a wait status: exit code 3 << 8
    EXPECT_EQ(jobs[3].describe(), "killed by signal 9");
    EXPECT_TRUE(jobs[4].succeeded());
}

// Slurm's --output expands %j and drops backslashes: '%' is doubled, a backslash refused.
TEST(Squeue, OutputPathsKeepPercentAndRefuseBackslash) {
    EXPECT_EQ(slurm_output_path("/a/100% é\n$(x)", "-o"), "/a/100%% é\n$(x)");
    try {
        slurm_output_path("/a\\b", "-o");
        ADD_FAILURE() << "a backslash was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Usage);
    }
}

TEST(Submit, UsageAndMissingClientErrorsSayTheFix) {
    TempDir tmp;
    const std::string shot = tmp.write("beam.toml", kShot);
    const auto no_executor = run_shatter({"submit", shot, "-o", tmp.file("out")});
    EXPECT_EQ(no_executor.exit_code, 2);
    EXPECT_NE(no_executor.err.find("--slurm"), std::string::npos) << no_executor.err;

    const auto unknown = run_shatter({"submit", shot, "--pbs", "-o", tmp.file("out")});
    EXPECT_EQ(unknown.exit_code, 2) << unknown.err;

    const auto backslash = run_shatter({"submit", shot, "--slurm", "-o", tmp.file("back\\slash")});
    EXPECT_EQ(backslash.exit_code, 2);
    EXPECT_NE(backslash.err.find("backslash"), std::string::npos) << backslash.err;

    ProcessOptions no_path;
    no_path.env = {{"PATH", tmp.file("empty")}};
    const ProcessResult missing = run_process({SHATTER_BINARY, "submit", shot, "--slurm", "-o", tmp.file("out")}, no_path);
    EXPECT_EQ(missing.exit_code, 6) << missing.err;
    EXPECT_NE(missing.err.find("apt-get install slurm-client"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace shatter
