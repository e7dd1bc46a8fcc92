// shatter submit SHOT|MESH|JOBS|FILE... --slurm [-o DIR] [--set K=V]... [--chunks N] [--partition P] [--account A]
//                [--time T] [--mem M] [--cpus N] [--sbatch-arg ARG]... [--shatter-bin PATH] [--wait]
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "cmd/command.h"
#include "core/error.h"
#include "pipeline/batch_file.h"
#include "pipeline/slurm_submit.h"

namespace shatter {

namespace {

struct SubmitFlags {
    std::vector<std::string> inputs;
    std::string output, cache;
    std::vector<std::string> overrides;
    bool slurm = false, wait = false;
    SubmitOptions options;
};

int run(SubmitFlags& f) {
    if (!f.slurm)
        throw Error(ExitCode::Usage, "submit: no executor given (fix: add --slurm; Slurm is the only executor "
                                     "shatter submits to, docs/cluster.md)");
    std::vector<RunSubmission> runs;
    SlurmJob sweep;
    // One shot or mesh; one batch file; or several shots and meshes, a batch of them.
    const bool batch_file = f.inputs.size() == 1 && is_batch_file(f.inputs.front());
    if (batch_file || f.inputs.size() > 1) {
        if (!f.cache.empty())
            throw Error(ExitCode::Usage, "--cache: a batch shares OUTPUT/.cache already (fix: leave --cache out)");
        runs = submit_batch(batch_file ? load_batch(f.inputs.front(), f.output, f.overrides)
                                       : batch_of_files(f.inputs, f.output, f.overrides),
                            f.options, &sweep);
    } else {
        RunOptions run;
        run.shot = f.inputs.front();
        run.overrides = f.overrides;
        run.output_dir = f.output;
        run.cache_dir = f.cache;
        runs.push_back(submit_run(std::filesystem::path(run.shot).stem().string(), run, f.options));
    }
    std::vector<SlurmJob> jobs;
    for (const RunSubmission& r : runs) {
        std::fputs(format_submission(r).c_str(), stdout);
        jobs.insert(jobs.end(), r.jobs.begin(), r.jobs.end());
    }
    if (!sweep.id.empty()) {
        std::fputs(fmt::format("sweep job {}: strips, plots and tables into {}/JOB/, log in {}/\n", sweep.id,
                               std::filesystem::path(sweep.log_dir).parent_path().string(), sweep.log_dir).c_str(),
                   stdout);
        jobs.push_back(sweep);
    }
    std::fflush(stdout);
    if (!f.wait) return 0;

    const std::vector<std::string> failed =
        wait_for_jobs(jobs, f.options.slurm, [](const std::string& line) { fmt::print(stderr, "submit: {}\n", line); });
    if (failed.empty()) {
        fmt::print(stdout, "all {} job{} succeeded\n", jobs.size(), jobs.size() == 1 ? "" : "s");
        return 0;
    }
    for (const std::string& line : failed) fmt::print(stderr, "FAILED: {}\n", line);
    fmt::print(stderr, "submit again after fixing: finished stages are reused\n");
    return static_cast<int>(ExitCode::Differs);
}

}  // namespace

RunCommand add_submit_command(CLI::App& root) {
    auto f = std::make_shared<SubmitFlags>();
    CLI::App* c = root.add_subcommand(
        "submit", "Run a shot, a mesh, a batch file, or several shots and meshes (as shatter batch) on a Slurm cluster "
                  "(docs/cluster.md): prescore and simulate as one job, "
                  "render as a job array over frame chunks after it, encode and summary as a final job. Frames are "
                  "the bytes of a local run. Stages that are up to date, and jobs still queued from an earlier "
                  "submit, are not submitted again. With --wait: exit code 1 naming each failed task.");
    c->add_option("input", f->inputs,
                  "the shot file (.toml) or mesh file, a batch file (.toml with [[job]] tables), or several shots and "
                  "meshes")
        ->required();
    c->add_flag("--slurm", f->slurm, "submit to Slurm with sbatch (required: the only executor so far)");
    c->add_option("-o,--output", f->output,
                  option_help("the output folder, visible at the same path on every node", "",
                              "out/SHOT-NAME, or the batch file's; for several files, out/batch"));
    c->add_option("--set", f->overrides,
                  "override a shot setting, SECTION.KEY=VALUE (repeatable; as shatter run; in every run of a batch, "
                  "as shatter batch)")
        ->allow_extra_args(false);
    c->add_option("--cache", f->cache, option_help("a stage cache shared between runs (as shatter run)", "", "none"));
    c->add_option("--chunks", f->options.chunks, option_help("render array tasks", "", "one per 30 frames"))
        ->check(CLI::Range(1, 10000));
    c->add_option("--partition", f->options.slurm.partition, option_help("sbatch --partition", "", "the cluster's"));
    c->add_option("--account", f->options.slurm.account, option_help("sbatch --account", "", "the cluster's"));
    c->add_option("--time", f->options.slurm.time,
                  option_help("time limit per job, in Slurm's format (e.g. 30, 2:00:00)", "", "the partition's"));
    c->add_option("--mem", f->options.slurm.mem, option_help("memory per job (e.g. 4G)", "", "the partition's"));
    c->add_option("--cpus", f->options.slurm.cpus, option_help("CPUs per job (sbatch --cpus-per-task)", "", "the partition's"))
        ->check(CLI::Range(1, 4096));
    c->add_option("--sbatch-arg", f->options.slurm.extra_args,
                  "one more sbatch flag for every job, written with '=' (repeatable), e.g. --sbatch-arg=--qos=high")
        ->allow_extra_args(false);
    c->add_option("--shatter-bin", f->options.shatter,
                  option_help("the shatter executable on the nodes", "", "this one, at the same path"));
    c->add_flag("--wait", f->wait, "wait until every job has ended; exit code 1 naming each failed task");
    return [f] { return run(*f); };
}

}  // namespace shatter
