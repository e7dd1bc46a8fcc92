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
    std::string path;                     // the batch file; "" for files given by name (batch_of_files)
    std::vector<std::string> overrides;   // --set: in every run (load_batch, batch_of_files)
    std::string output_dir;
    uint32_t workers = 2;
    std::vector<BatchJob> jobs;
    std::string cache_dir() const;  // OUTPUT/.cache
};

// Reads and checks a batch file: syntax, unknown keys, types, empty sweeps and duplicate job
// names are Error(BadInput) naming file:line. The shots themselves are read when their runs start
// (a bad shot fails its job only). `output_dir` replaces [batch] output when not empty;
// `overrides` (SECTION.KEY=VALUE) go to every run after its job's `set` and before its sweep's
// values.
BatchFile load_batch(const std::string& path, const std::string& output_dir = "",
                     const std::vector<std::string>& overrides = {});

// A batch of shots and mesh files given by name (`shatter batch a.obj b.stl c.toml`): one job
// and one run each, named by the file (a second file of the same name gets its extension, then a
// number: "horse", "horse-stl", "horse-stl-2"), every run with `overrides`, into `output_dir`
// (default out/batch). A file that is not there is Error(BadInput), a batch file among them
// Error(Usage), before anything runs.
BatchFile batch_of_files(const std::vector<std::string>& files, const std::string& output_dir = "",
                         const std::vector<std::string>& overrides = {});

// True for a batch file (a .toml file with [[job]] tables or a [batch] table) rather than a shot
// or a mesh.
bool is_batch_file(const std::string& path);

}  // namespace shatter
