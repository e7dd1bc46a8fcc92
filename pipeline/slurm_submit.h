// `shatter submit --slurm`: the work of `shatter run` as a chain of Slurm jobs per run.
//
//    simulate job ──afterok──► render array (task i = --chunk i/N) ──afterok──► finish job
//    shatter run --stages       shatter run --stages render             shatter run (every stage:
//    prescore,simulate          --chunk $SLURM_ARRAY_TASK_ID/N          encode, sheet, plot, export,
//                                                                       summary.json; the rest skipped)
//
// A batch file adds one sweep job after every run's finish job (`shatter batch`, whose runs are
// all up to date by then, makes the strips, plots and tables). Every job runs one static script
// (slurm_job_script()): the command is its argument vector, so no path, name or --set value is
// ever shell text. Jobs wait with --dependency=afterok and --kill-on-invalid-dep=yes, so the
// dependents of a failed job are cancelled instead of pending forever.
//
// Frames are the bytes a local run writes: the jobs run the same `shatter run`, and a frame does
// not depend on its chunk. Resubmission reuses what is there: stages whose stamps are current
// get no job, and jobs of an earlier submit that are still queued or running (OUT/slurm/jobs.json,
// checked with squeue) are waited for instead of submitted again. docs/cluster.md is the guide.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pipeline/batch_file.h"
#include "pipeline/run.h"
#include "pipeline/slurm.h"

namespace shatter {

struct SubmitOptions {
    SlurmSettings slurm;
    std::string shatter;   // the shatter executable the jobs run, at the same path on every node ("" = this one)
    uint32_t chunks = 0;   // render array tasks (0: one per 30 frames); at most the number of frames
};

// One job of a chain.
struct SlurmJob {
    std::string kind;           // "simulate", "render", "finish" or "sweep"
    std::string id;             // Slurm's job id (the array's for render)
    bool reused = false;        // queued or running from an earlier submit: not submitted again
    uint32_t tasks = 0;         // render: array tasks (0 for a plain job)
    uint32_t frames = 0;        // render: frames of the run (for the frame ranges in messages)
    std::string log_dir;        // its logs: KIND-ID.log, render-ID_TASK.log
    std::string label;          // the run (or batch) it belongs to, for messages
};

// What `submit` did for one run.
struct RunSubmission {
    std::string label;                 // the shot's name, or JOB/LABEL of a batch run
    RunOptions run;                    // absolute shot, output and cache paths
    uint32_t frames = 0, chunks = 1;
    std::vector<SlurmJob> jobs;        // in chain order; stages that are up to date have none
    std::vector<Stage> up_to_date;     // stages whose outputs were current at submission
};

// The job script every job runs (written to OUT/slurm/job.sh).
const char* slurm_job_script();

// Submits the chain of one run (`run.shot`, `run.output_dir` and `run.cache_dir` absolute or
// relative to the current directory). Bad input (the shot) throws before anything is submitted;
// jobs of an earlier submit with other settings that are still active are an Error(Usage).
RunSubmission submit_run(const std::string& label, const RunOptions& run, const SubmitOptions& options);

// Submits the runs of a batch file, then the sweep job after all of them.
std::vector<RunSubmission> submit_batch(const BatchFile& batch, const SubmitOptions& options, SlurmJob* sweep);

// Polls squeue until every job has ended. `on_change` gets a line whenever a job's state changes.
// Returns one message per job or task that did not succeed, the causes first, e.g.
// "render task 2 of job 1234 (frames 60..89) failed: exit code 3; log: OUT/slurm/render-1234_2.log".
std::vector<std::string> wait_for_jobs(const std::vector<SlurmJob>& jobs, const SlurmSettings& settings,
                                       const std::function<void(const std::string&)>& on_change);

// "bunny: prescore, simulate up to date; render array 13 (3 tasks), finish job 14" and the log folder.
std::string format_submission(const RunSubmission& submission);

}  // namespace shatter
