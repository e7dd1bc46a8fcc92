// The batch file of `shatter batch` and `shatter submit`: shots and parameter sweeps (TOML,
// docs/pipeline.md).
//
//   [batch]
//   workers = 2                  # parallel runs (shatter batch --workers overrides)
//   output = "out/sweep"         # default: out/BATCH-NAME, relative to the current directory
//
//   [[job]]
//   name = "bunny"               # default: the shot's name
//   shot = "bunny.toml"          # relative to the batch file
//   set = { "render.width" = 640 }                 # overrides for every run of the job
//   sweep = { "material.alpha" = [0, 0.5, 1, 2] }  # one run per value (several keys: every combination)
//   strip_time = 1.2             # s: the moment the sweep's strip shows (default: 0.5 s after the first break)
//
// Each run goes to OUTPUT/JOB/LABEL (LABEL e.g. "alpha-0.5", or "run" without a sweep); all runs
// share the stage cache OUTPUT/.cache, so an alpha sweep tetrahedralizes once.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shatter {

struct BatchRun {
    std::string label;                                       // "alpha-0.5_seed-2"; names its folder
    std::string caption;                                     // "alpha = 0.5, seed = 2" for strips and tables
    std::vector<std::string> overrides;                      // SECTION.KEY=VALUE: the job's, then the sweep's
    std::string output_dir;
};

struct BatchJob {
    std::string name;
    std::string shot;                         // the shot file, relative to the current directory
    std::vector<std::string> sweep_keys;      // in file order
    std::vector<BatchRun> runs;               // every combination, the first key varying slowest
    std::optional<double> strip_time;         // (unit: s)
    std::string output_dir;                   // OUTPUT/JOB
};

struct BatchFile {
    std::string path;
    std::string output_dir;
    uint32_t workers = 2;
    std::vector<BatchJob> jobs;
    std::string cache_dir() const;  // OUTPUT/.cache
};

// Reads and checks a batch file: syntax, unknown keys, types, empty sweeps and duplicate job
// names are Error(BadInput) naming file:line. The shots themselves are read when their runs start
// (a bad shot fails its job only). `output_dir` replaces [batch] output when not empty.
BatchFile load_batch(const std::string& path, const std::string& output_dir = "");

// True for a batch file (.batch.toml or a TOML file with [[job]] tables) rather than a shot.
bool is_batch_file(const std::string& path);

}  // namespace shatter
