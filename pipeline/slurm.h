// Slurm's command-line clients as a small library: submit a batch job with sbatch and read the
// states of jobs and array tasks with squeue. Every call is an argv vector through posix_spawn
// (pipeline/process.h), never a shell string, so paths and names reach Slurm byte for byte.
//
// Accounting may be off (no slurmdbd, so no sacct): squeue -t all still lists a finished job, with
// its state and exit code, for MinJobAge seconds after it ended (300 s by default), which is what
// `shatter submit --wait` polls. A job squeue no longer knows is reported as "unknown".
//
// Slurm pitfalls handled here (docs/cluster.md):
//   - --output expands %j, %A, %a...: a literal '%' in a path is written "%%".
//   - --output drops every backslash and then expands nothing: a path with '\' cannot be
//     expressed, so it is refused with a clear error instead of a job that cannot start.
//   - a pending array task that is cancelled before it starts leaves no record at all.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace shatter {

// How jobs are placed on the cluster; every field "" or 0 means the cluster's default.
struct SlurmSettings {
    std::string partition;                 // sbatch --partition
    std::string account;                   // sbatch --account
    std::string time;                      // sbatch --time per job, Slurm's format (e.g. "30", "2:00:00")
    std::string mem;                       // sbatch --mem per job (e.g. "4G")
    uint32_t cpus = 0;                     // sbatch --cpus-per-task
    std::vector<std::string> extra_args;   // more sbatch flags, one argv element each (--sbatch-arg)
    std::string sbatch = "sbatch";         // the clients: a name on PATH or a path
    std::string squeue = "squeue";
};

// One batch job.
struct JobRequest {
    std::string name;                   // --job-name
    std::string script;                 // the batch script file (read by sbatch at submission)
    std::vector<std::string> args;      // the script's arguments ($1, $2, ...)
    std::string workdir;                // --chdir: an absolute path
    std::string log;                    // --output (stdout and stderr): a path in which %j, %A and %a
                                        // stand for the job id, array job id and task; other '%' are literal
    std::string array;                  // --array, e.g. "0-3" ("" = not an array)
    std::vector<std::string> after_ok;  // ids of jobs it waits for; it is cancelled when one fails
};

// The argv of the sbatch call for `job` (exposed for messages and tests).
std::vector<std::string> sbatch_argv(const SlurmSettings& settings, const JobRequest& job);

// Submits `job` and returns its id. Throws Error(Tool) when sbatch is missing or refuses the job
// (its message included), Error(Usage) for a log path Slurm cannot express.
std::string submit_job(const SlurmSettings& settings, const JobRequest& job);

// `path` with every '%' doubled, for --output. Throws Error(Usage) naming `where` when the path
// holds a backslash (Slurm drops backslashes from --output).
std::string slurm_output_path(const std::string& path, const std::string& where);

// What squeue says about one job, or one task of an array job.
struct JobStatus {
    std::string job_id;               // for an array task: the array's job id
    std::optional<uint32_t> task;     // the array task index (unset for a plain job or a pending range)
    std::vector<uint32_t> pending;    // a pending array's tasks that have no record of their own yet
    std::string state;                // Slurm's: PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, ...
    std::string reason;               // e.g. NonZeroExitCode, Dependency, DependencyNeverSatisfied
    int exit_code = 0;                // of the batch script, when it ended
    int signal = 0;                   // that killed it, or 0
    bool finished() const;            // in a final state
    bool succeeded() const;           // COMPLETED with exit code 0
    std::string describe() const;     // "exit code 3", "cancelled (DependencyNeverSatisfied)", "TIMEOUT"
};

// Every record squeue has for the given job ids (array tasks one by one). Ids squeue has forgotten
// have no record. Throws Error(Tool) when squeue is missing or fails.
std::vector<JobStatus> query_jobs(const SlurmSettings& settings, const std::vector<std::string>& job_ids);

// Parses squeue's "--noheader -O JobID:|,ArrayJobID:|,ArrayTaskID:|,State:|,exit_code:|,Reason:|"
// output (exposed for tests).
std::vector<JobStatus> parse_squeue(const std::string& text);

// The error for a missing Slurm client, with the fix.
[[noreturn]] void throw_missing_slurm_client(const std::string& program);

}  // namespace shatter
