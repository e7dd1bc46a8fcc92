// submit_run and submit_batch (pipeline/slurm_submit.h): decide which jobs a run needs, submit
// them with their dependencies and record them in OUT/slurm/jobs.json.
#include "pipeline/slurm_submit.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/shot.h"
#include "pipeline/process.h"
#include "simulate/simulate.h"

namespace shatter {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

// The job script. Static text: the whole command arrives as arguments ("$@"); for a render task
// the script only appends --chunk with Slurm's task index.
constexpr const char* kJobScript = R"sh(#!/bin/sh
# A job of `shatter submit` (pipeline/slurm_submit.cpp, docs/cluster.md). This text is the same
# for every job: the command (the shatter executable, the shot, the output folder, the --set
# overrides) arrives as arguments, so no path or value is ever read as shell code.
#   job.sh COMMAND...                 runs COMMAND
#   job.sh --chunks N COMMAND...      runs COMMAND --chunk $SLURM_ARRAY_TASK_ID/N (a render array task)
set -u
echo "shatter job ${SLURM_JOB_ID:-?}${SLURM_ARRAY_TASK_ID:+ (task $SLURM_ARRAY_TASK_ID)} on $(hostname)"
if [ "$1" = "--chunks" ]; then
    chunks=$2
    shift 2
    exec "$@" --chunk "${SLURM_ARRAY_TASK_ID:?a render job must be an array job}/$chunks"
fi
exec "$@"
)sh";

constexpr int kJobsFormatVersion = 1;

std::string absolute(const std::string& path) { return path.empty() ? path : fs::absolute(path).lexically_normal().string(); }

// A job name Slurm shows in squeue: the kind and the run, in plain characters.
std::string job_name(const std::string& kind, const std::string& label) {
    std::string name = "shatter-" + kind + "-";
    for (unsigned char c : label) name += std::isalnum(c) || c == '.' || c == '-' || c == '_' ? char(c) : '_';
    return name.substr(0, 64);
}

bool has(const std::vector<Stage>& stages, Stage s) { return std::find(stages.begin(), stages.end(), s) != stages.end(); }

// One run's chain: what was there before and what is submitted now.
class RunChain {
public:
    RunChain(std::string label, const RunOptions& run, const SubmitOptions& options)
        : options_(options), slurm_dir_((fs::path(run.output_dir) / "slurm").string()) {
        sub_.label = std::move(label);
        sub_.run = run;
        shatter_ = options.shatter.empty() ? own_executable() : absolute(options.shatter);
        const Shot shot = load_shot_or_mesh(run.shot, run.overrides);  // bad input stops here, before any job
        sub_.frames = frame_count(shot.simulate);
        const uint32_t wanted = options.chunks ? options.chunks : (sub_.frames + 29) / 30;
        sub_.chunks = std::clamp<uint32_t>(wanted, 1, std::max<uint32_t>(sub_.frames, 1));
        slurm_output_path(slurm_dir_, "-o/--output");  // refuses what Slurm cannot write to, early
    }

    RunSubmission submit() {
        make_directories(slurm_dir_);
        write_file_atomic(script(), kJobScript);
        const std::vector<SlurmJob> active = still_active();
        sub_.up_to_date = up_to_date_stages(sub_.run);

        const SlurmJob* sim = find(active, "simulate");
        if (sim)
            sub_.jobs.push_back(*sim);
        else if (!(has(sub_.up_to_date, Stage::Prescore) && has(sub_.up_to_date, Stage::Simulate)))
            add_job("simulate", {"--stages", "prescore,simulate"}, "", {});

        const SlurmJob* render = find(active, "render");
        if (render)
            sub_.jobs.push_back(*render);
        else if (!sub_.jobs.empty() || !has(sub_.up_to_date, Stage::Render))
            add_job("render", {"--stages", "render"}, fmt::format("0-{}", sub_.chunks - 1), ids());

        const SlurmJob* finish = find(active, "finish");
        if (finish)
            sub_.jobs.push_back(*finish);
        else
            add_job("finish", {}, "", ids());
        record();
        return std::move(sub_);
    }

private:
    std::string script() const { return (fs::path(slurm_dir_) / "job.sh").string(); }
    std::string jobs_file() const { return (fs::path(slurm_dir_) / "jobs.json").string(); }

    std::vector<std::string> ids() const {
        std::vector<std::string> out;
        for (const SlurmJob& j : sub_.jobs) out.push_back(j.id);
        return out;
    }

    static const SlurmJob* find(const std::vector<SlurmJob>& jobs, const std::string& kind) {
        for (const SlurmJob& j : jobs)
            if (j.kind == kind) return &j;
        return nullptr;
    }

    // `shatter run` with this run's shot, output, cache and overrides, then `extra`.
    std::vector<std::string> run_command(const std::vector<std::string>& extra) const {
        std::vector<std::string> argv = {shatter_, "run", sub_.run.shot, "-o", sub_.run.output_dir, "--no-progress"};
        if (!sub_.run.cache_dir.empty()) argv.insert(argv.end(), {"--cache", sub_.run.cache_dir});
        for (const std::string& o : sub_.run.overrides) argv.insert(argv.end(), {"--set", o});
        argv.insert(argv.end(), extra.begin(), extra.end());
        return argv;
    }

    void add_job(const std::string& kind, const std::vector<std::string>& stages, const std::string& array,
                 const std::vector<std::string>& after) {
        JobRequest req;
        req.name = job_name(kind, sub_.label);
        req.script = script();
        if (!array.empty()) req.args = {"--chunks", std::to_string(sub_.chunks)};
        const std::vector<std::string> command = run_command(stages);
        req.args.insert(req.args.end(), command.begin(), command.end());
        req.workdir = sub_.run.output_dir;
        const std::string dir = slurm_output_path(slurm_dir_, "-o/--output");
        req.log = dir + (array.empty() ? "/" + kind + "-%j.log" : "/" + kind + "-%A_%a.log");
        req.array = array;
        req.after_ok = after;
        SlurmJob job;
        job.kind = kind;
        job.id = submit_job(options_.slurm, req);
        job.tasks = array.empty() ? 0 : sub_.chunks;
        job.frames = sub_.frames;
        job.log_dir = slurm_dir_;
        job.label = sub_.label;
        sub_.jobs.push_back(job);
        spdlog::debug("submit: {} job {} for {}", kind, job.id, sub_.label);
        record();  // after every job, so that an interrupted submit still knows what it started
    }

    // The jobs of an earlier submit (jobs.json) that squeue still lists as queued or running.
    std::vector<SlurmJob> still_active() const {
        std::error_code ec;
        if (!fs::exists(jobs_file(), ec)) return {};
        json before;
        try {
            before = json::parse(read_file(jobs_file(), "jobs file"));
        } catch (const std::exception& e) {
            spdlog::warn("{}: unreadable ({}); treating its jobs as finished", jobs_file(), e.what());
            return {};
        }
        std::vector<SlurmJob> jobs;
        std::vector<std::string> ids;
        for (const json& j : before.value("jobs", json::array())) {
            SlurmJob job;
            job.kind = j.value("kind", "");
            job.id = j.value("id", "");
            job.tasks = j.value("tasks", 0u);
            job.frames = before.value("frames", 0u);
            job.log_dir = slurm_dir_;
            job.label = sub_.label;
            job.reused = true;
            if (!job.id.empty()) jobs.push_back(job), ids.push_back(job.id);
        }
        std::set<std::string> active;
        for (const JobStatus& s : query_jobs(options_.slurm, ids))
            if (!s.finished()) active.insert(s.job_id);
        std::erase_if(jobs, [&](const SlurmJob& j) { return !active.count(j.id); });
        if (!jobs.empty() && (before.value("shot", "") != sub_.run.shot ||
                              before.value("overrides", std::vector<std::string>{}) != sub_.run.overrides ||
                              before.value("cache_dir", "") != sub_.run.cache_dir)) {
            std::string list;
            for (const SlurmJob& j : jobs) list += " " + j.id;
            throw Error(ExitCode::Usage,
                        fmt::format("{}: jobs{} of an earlier submit with another shot or other --set values are still "
                                    "queued or running into this folder (fix: wait for them, or scancel{}; or submit "
                                    "into another -o folder)", sub_.run.output_dir, list, list));
        }
        return jobs;
    }

    void record() const {
        json j;
        j["format"] = "shatter-slurm-jobs";
        j["version"] = kJobsFormatVersion;
        j["shot"] = sub_.run.shot;
        j["overrides"] = sub_.run.overrides;
        j["output_dir"] = sub_.run.output_dir;
        j["cache_dir"] = sub_.run.cache_dir;
        j["frames"] = sub_.frames;
        j["chunks"] = sub_.chunks;
        json up = json::array();
        for (Stage s : sub_.up_to_date) up.push_back(to_string(s));
        j["up_to_date"] = up;
        json jobs = json::array();
        for (const SlurmJob& job : sub_.jobs) {
            json e = {{"kind", job.kind}, {"id", job.id}, {"reused", job.reused}};
            if (job.tasks) e["tasks"] = job.tasks;
            e["log"] = (fs::path(slurm_dir_) / (job.tasks ? job.kind + "-" + job.id + "_%a.log"
                                                          : job.kind + "-" + job.id + ".log")).string();
            jobs.push_back(e);
        }
        j["jobs"] = jobs;
        write_file_atomic(jobs_file(), j.dump(2) + "\n");
    }

    const SubmitOptions& options_;
    std::string slurm_dir_, shatter_;
    RunSubmission sub_;
};

}  // namespace

const char* slurm_job_script() { return kJobScript; }

RunSubmission submit_run(const std::string& label, const RunOptions& run, const SubmitOptions& options) {
    RunOptions abs = run;
    abs.shot = absolute(run.shot);
    abs.output_dir = absolute(run.output_dir.empty() ? default_output_dir(run.shot) : run.output_dir);
    abs.cache_dir = absolute(run.cache_dir);
    abs.stages.clear();
    abs.chunk = 0;
    abs.chunks = 1;
    return RunChain(label, abs, options).submit();
}

std::vector<RunSubmission> submit_batch(const BatchFile& batch, const SubmitOptions& options, SlurmJob* sweep) {
    // Every shot is read before the first job goes out.
    for (const BatchJob& job : batch.jobs)
        for (const BatchRun& r : job.runs) (void)load_shot_or_mesh(job.shot, r.overrides);
    std::vector<RunSubmission> out;
    std::vector<std::string> finish_ids;
    for (const BatchJob& job : batch.jobs)
        for (const BatchRun& r : job.runs) {
            RunOptions run;
            run.shot = job.shot;
            run.overrides = r.overrides;
            run.output_dir = r.output_dir;
            run.cache_dir = batch.cache_dir();
            out.push_back(submit_run(job.name + "/" + r.label, run, options));
            finish_ids.push_back(out.back().jobs.back().id);
        }
    if (!sweep) return out;

    // The sweep outputs: `shatter batch` over runs that are all up to date by then.
    const std::string dir = absolute(batch.output_dir), slurm_dir = (fs::path(dir) / "slurm").string();
    make_directories(slurm_dir);
    write_file_atomic((fs::path(slurm_dir) / "job.sh").string(), kJobScript);
    JobRequest req;
    // The batch file, or the files given by name, with the same --set overrides.
    const std::string label = batch.path.empty() ? fs::path(dir).filename().string() : fs::path(batch.path).stem().string();
    req.name = job_name("sweep", label);
    req.script = (fs::path(slurm_dir) / "job.sh").string();
    req.args = {options.shatter.empty() ? own_executable() : absolute(options.shatter), "batch"};
    if (batch.path.empty())
        for (const BatchJob& job : batch.jobs) req.args.push_back(absolute(job.shot));  // the files, in order
    else
        req.args.push_back(absolute(batch.path));
    for (const std::string& o : batch.overrides) req.args.insert(req.args.end(), {"--set", o});
    req.args.insert(req.args.end(), {"-o", dir, "--quiet", "--workers", std::to_string(std::max<uint32_t>(1, options.slurm.cpus))});
    req.workdir = dir;
    req.log = slurm_output_path(slurm_dir, "-o/--output") + "/sweep-%j.log";
    req.after_ok = finish_ids;
    sweep->kind = "sweep";
    sweep->id = submit_job(options.slurm, req);
    sweep->log_dir = slurm_dir;
    sweep->label = label;
    write_file_atomic((fs::path(slurm_dir) / "sweep.json").string(),
                      json{{"format", "shatter-slurm-jobs"}, {"version", kJobsFormatVersion},
                           {"jobs", json::array({{{"kind", "sweep"}, {"id", sweep->id}}})}}.dump(2) + "\n");
    return out;
}

std::string format_submission(const RunSubmission& s) {
    std::vector<std::string> parts;
    if (!s.up_to_date.empty()) {
        std::string up;
        for (Stage st : s.up_to_date) up += (up.empty() ? "" : ", ") + std::string(to_string(st));
        parts.push_back(up + " up to date");
    }
    for (const SlurmJob& j : s.jobs) {
        const std::string what = j.kind == "simulate" ? "prescore/simulate job" : j.kind == "render" ? "render array" : "finish job";
        parts.push_back(fmt::format("{} {}{}{}", what, j.id, j.tasks ? fmt::format(" ({} tasks)", j.tasks) : "",
                                    j.reused ? " (still queued or running from an earlier submit)" : ""));
    }
    std::string out = s.label + ": ";
    for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
    return out + fmt::format("\n  {} frames in {} chunks; logs and jobs.json in {}/slurm/\n", s.frames, s.chunks,
                             s.run.output_dir);
}

}  // namespace shatter
