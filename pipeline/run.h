// `shatter run SHOT`: one shot from mesh to movie, into one output folder.
//
//   prescore ─► simulate ─► render ─► encode (MP4) ─► sheet (contact sheet) ─► plot (energy PNG)
//                                                  ─► export (.glb) ─► summary.json ─► report (report.html)
//
// When render runs, encode, plot and export run beside it (threads; ffmpeg and python3 are
// processes of their own): encode takes each frame as render writes it, plot and export read
// only the model, the trajectory and the energy series. They are waited for before summary.json.
//
// Every stage is stamped with a key over what it read (pipeline/stage_cache.h): a re-run skips
// the stages that are up to date, a killed run resumes where it stopped (frames one by one), and
// the final bytes do not depend on how often the run was interrupted. The output folder:
//
//   NAME.model  NAME.pieces.ply  NAME.traj  NAME.breaks.jsonl  NAME.energy.csv  NAME.instability.json
//   frames/  NAME.mp4  NAME.contact.png  NAME.energy.png  NAME.glb  summary.json  run.log  .shatter/
//   report.html  report.times.js  viewer/   (the page of the run: pipeline/report_page.h)
//
// NAME is the shot file's stem. NAME.instability.json says what simulate's instability guard did
// (clamps, or where it stopped; pipeline/instability_record.h); summary.json repeats it as
// "instability".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace shatter {

enum class Stage : uint8_t { Prescore, Simulate, Render, Encode, Sheet, Plot, Export, Report };
inline constexpr Stage kAllStages[] = {Stage::Prescore, Stage::Simulate, Stage::Render, Stage::Encode,
                                       Stage::Sheet,    Stage::Plot,     Stage::Export, Stage::Report};
const char* to_string(Stage stage);
std::optional<Stage> parse_stage(const std::string& text);

struct RunOptions {
    std::string shot;                    // the shot file (.toml)
    std::vector<std::string> overrides;  // SECTION.KEY=VALUE (core/shot.h)
    std::string output_dir;              // "" = out/NAME
    std::string cache_dir;               // shared stage cache of prescore and simulate ("" = none)
    std::vector<Stage> stages;           // the stages to run, in pipeline order; empty = all
    uint32_t chunk = 0, chunks = 1;      // render only chunk `chunk` (from 0) of `chunks` equal frame ranges
    bool force = false;                  // run stages even when they are up to date
    bool progress = true;                // progress bars on stderr
};

enum class StageOutcome : uint8_t { Ran, UpToDate, FromCache, NotAsked, Failed };
const char* to_string(StageOutcome outcome);

struct StageReport {
    Stage stage;
    StageOutcome outcome = StageOutcome::NotAsked;
    double seconds = 0;   // wall time (unit: s)
    std::string error;    // when it failed
    bool beside_render = false;  // ran beside render, its time overlapping render's (encode, plot, export)
};

struct RunResult {
    std::string output_dir;
    std::string name;                   // NAME of the files
    std::vector<StageReport> stages;    // in pipeline order
    double seconds = 0;                 // the run's wall time, less than the stages' sum when some ran beside render (unit: s)
    nlohmann::ordered_json summary;     // what summary.json holds (empty until simulate has run)
    int exit_code = 0;                  // 0, or the exit code of the first failure (core/error.h)
    std::vector<std::string> warnings;  // what this run's stages warned of, each once, in order
};

// The frames `--chunk chunk/chunks` renders: the chunk-th of `chunks` equal ranges of [0, frames),
// as [first, end).
std::pair<uint32_t, uint32_t> chunk_frames(uint32_t frames, uint32_t chunk, uint32_t chunks);

// out/NAME for a shot file path.
std::string default_output_dir(const std::string& shot);

// Runs the asked stages. Bad input to the first stages (shot, mesh) throws Error before any output
// is touched; a failing finishing stage (encode, sheet, plot, export) is reported in the result
// and the others still run.
RunResult run_shot(const RunOptions& options);

// The stages whose outputs in the output folder are up to date for this shot and these overrides
// (prescore, simulate, render: their stamps match and, for render, every frame is there), without
// running or writing anything. Bad input throws as run_shot does. For `shatter submit`.
std::vector<Stage> up_to_date_stages(const RunOptions& options);

// The closing summary printed at the end: time per stage, pieces, breaks, energy, the instability
// guard's clamps or stop (a "stability:" line when there were any, or clamp was asked for), files.
std::string format_run_summary(const RunResult& result);

}  // namespace shatter
