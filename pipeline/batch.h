// `shatter batch JOBS`: every run of a batch file (pipeline/batch_file.h), N at a time, each in
// its own `shatter run` process (a crash or bad shot fails that run only), sharing one stage
// cache. Per sweep: a strip (one panel per run at the same moment), an energy plot (one curve per
// run) and a table (breaks, energies, speeds) in OUTPUT/JOB/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/batch_file.h"

namespace shatter {

struct BatchOptions {
    uint32_t workers = 0;      // 0: the batch file's
    std::string shatter;       // the `shatter` executable to run ("" = this process's own)
    bool progress = true;      // a line per finished run on stderr
};

struct BatchRunResult {
    std::string job, label, caption, output_dir;
    int exit_code = -1;        // of its `shatter run`
    std::string error;         // its last error line, when it failed
    double seconds = 0;        // (unit: s) wall time
    nlohmann::json summary;    // its summary.json (null when it failed early)
};

struct BatchResult {
    std::vector<BatchRunResult> runs;  // in batch-file order
    std::vector<std::string> made;     // strips, plots and tables written
    std::vector<std::string> problems; // sweep outputs that could not be made
    int exit_code = 0;                 // 0 when every run succeeded, else 1 (ExitCode::Differs)
};

// Runs every run, then per sweep the strip, plot and table, then OUTPUT/index.html (pipeline/batch_page.h).
BatchResult run_batch(const BatchFile& batch, const BatchOptions& options);

// The moment a job's strip shows (and the batch page's thumbnails): the job's strip_time, else
// 0.5 s after the latest first break of its successful runs (unit: s).
double strip_moment(const BatchJob& job, const std::vector<const BatchRunResult*>& ok);
// The frame of a successful run nearest `when` (the last one at most), relative to its folder.
std::string frame_at(const BatchRunResult& run, double when);

// The closing table: one row per run.
std::string format_batch_table(const BatchResult& result);

}  // namespace shatter
