// shatter batch JOBS|SHOT|MESH... [-o DIR] [--workers N] [--set SECTION.KEY=VALUE]...
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "cmd/command.h"
#include "core/error.h"
#include "core/shot.h"
#include "core/toml_reader.h"
#include "pipeline/batch.h"
#include "pipeline/batch_file.h"

namespace shatter {

namespace {

struct BatchFlags {
    std::vector<std::string> inputs, overrides;
    std::string output;
    uint32_t workers = 0;
    bool quiet = false;
};

// One batch file, or shots and meshes given by name. A lone .toml file that does not read as TOML
// is taken as a batch file, so that its error names its line.
bool one_batch_file(const std::vector<std::string>& inputs) {
    if (inputs.size() != 1 || std::filesystem::path(inputs.front()).extension() != ".toml") return false;
    if (is_batch_file(inputs.front())) return true;
    try {
        parse_toml_file(inputs.front());
        return false;
    } catch (const Error&) {
        return true;
    }
}

int run(const BatchFlags& f) {
    const bool file = one_batch_file(f.inputs);
    const BatchFile batch =
        file ? load_batch(f.inputs.front(), f.output, f.overrides) : batch_of_files(f.inputs, f.output, f.overrides);
    // A bad --set would fail every run: it is refused before any starts, read against the first
    // shot that reads without it (a bad shot fails its own job only).
    if (!f.overrides.empty())
        for (const BatchJob& job : batch.jobs) {
            try {
                load_shot_or_mesh(job.shot);
            } catch (const Error&) {
                continue;
            }
            load_shot_or_mesh(job.shot, f.overrides);
            break;
        }
    BatchOptions options;
    options.workers = f.workers;
    options.progress = !f.quiet;
    size_t runs = 0;
    for (const BatchJob& j : batch.jobs) runs += j.runs.size();
    fmt::print(stderr, "batch: {} jobs, {} runs, {} at a time, into {}/\n", batch.jobs.size(), runs,
               f.workers ? f.workers : batch.workers, batch.output_dir);
    const BatchResult r = run_batch(batch, options);
    std::fputs(("\n" + format_batch_table(r)).c_str(), stdout);
    return r.exit_code;
}

}  // namespace

RunCommand add_batch_command(CLI::App& root) {
    auto f = std::make_shared<BatchFlags>();
    CLI::App* c = root.add_subcommand(
        "batch", "Run every shot and parameter sweep of a batch file (docs/pipeline.md), or every shot and mesh "
                 "given (shatter batch meshes/*.obj: the default shot on each), N runs at a time, sharing cached "
                 "stages (one prescore for an alpha sweep). A failed run is reported; the others finish. Per sweep: a "
                 "strip, an energy plot and a table; index.html, a row per run. Exit code 1 when any run failed.");
    c->add_option("jobs", f->inputs,
                  "the batch file (.toml with [[job]] tables), or shot files (.toml) and mesh files, each one job")
        ->required();
    c->add_option("-o,--output", f->output,
                  option_help("the output folder", "", "[batch] output, else out/BATCH-NAME; for files given by name, out/batch"));
    c->add_option("--set", f->overrides,
                  "override a shot setting in every run, SECTION.KEY=VALUE (repeatable; after a job's set, before its "
                  "sweep), e.g. --set render.width=640")
        ->allow_extra_args(false);
    c->add_option("--workers", f->workers, option_help("runs at a time", "", "[batch] workers, else 2"))
        ->check(CLI::Range(1, 256));
    c->add_flag("-q,--quiet", f->quiet, "no line per finished run");
    return [f] { return run(*f); };
}

}  // namespace shatter
