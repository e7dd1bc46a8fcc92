// shatter batch JOBS [-o DIR] [--workers N]
#include <cstdio>

#include <fmt/format.h>

#include "cmd/command.h"
#include "pipeline/batch.h"
#include "pipeline/batch_file.h"

namespace shatter {

namespace {

struct BatchFlags {
    std::string jobs, output;
    uint32_t workers = 0;
    bool quiet = false;
};

int run(const BatchFlags& f) {
    const BatchFile batch = load_batch(f.jobs, f.output);
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
        "batch", "Run every shot and parameter sweep of a batch file (docs/pipeline.md), N runs at a time, sharing cached "
                 "stages (one prescore for an alpha sweep). A failed run is reported; the others finish. Per sweep: a "
                 "strip, an energy plot and a table. Exit code 1 when any run failed.");
    c->add_option("jobs", f->jobs, "the batch file (.toml with [[job]] tables)")->required();
    c->add_option("-o,--output", f->output, option_help("the output folder", "", "[batch] output, else out/BATCH-NAME"));
    c->add_option("--workers", f->workers, option_help("runs at a time", "", "[batch] workers, else 2"))
        ->check(CLI::Range(1, 256));
    c->add_flag("-q,--quiet", f->quiet, "no line per finished run");
    return [f] { return run(*f); };
}

}  // namespace shatter
