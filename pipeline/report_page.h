// OUT/report.html, the page of one `shatter run`: the movie, the contact sheet, the energy plot,
// the energy books (stored, injected, alpha), the summary (pieces, constraints, breaks,
// fragments), the time of each stage, what prescore and simulate chose and why, the shot's
// settings, a link to every file, and a 3D view of NAME.glb with its animation (orbit, play,
// scrub).
//
// The page works from file:// with no network (Chromium lets a file:// page neither fetch() its
// neighbours nor import ES modules from them):
//  - the .glb is embedded in the page as base64 and parsed in memory;
//  - the 3D view is three.js r147's classic-script build (three.min.js, GLTFLoader.js,
//    OrbitControls.js: the last release with classic scripts of the loaders), loaded with plain
//    <script src> from OUT/viewer/, where the run copies them from the npm package `three` that
//    scripts/install-node-tools.sh installs into BUILD/node_modules (find_viewer() below). Without
//    it the page has everything but the 3D view, and a note saying how to get it;
//  - the stage times, which differ from run to run, are in OUT/report.times.js (a classic script
//    setting window.shatterStageTimes, rewritten by every run, like run.log), so that the page
//    itself is the same bytes for the same inputs.
// Every number of summary.json the page shows carries data-key (the JSON pointer into
// summary.json) and data-value (the exact JSON value), so that a test can compare them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "pipeline/run.h"

namespace shatter {

struct Shot;

// The files of the viewer: {path in the npm package `three`, name in OUT/viewer/}.
struct ViewerFile {
    const char* package_path;
    const char* name;
};
extern const std::vector<ViewerFile> kViewerFiles;
// The version of `three` the viewer is written for (scripts/install-node-tools.sh pins it).
extern const char* const kViewerVersion;

// The folder of the npm package `three` at kViewerVersion: $SHATTER_NODE_MODULES/three when that
// variable is set, else EXE_DIR/../node_modules/three (the build tree: BUILD/bin/shatter and
// BUILD/node_modules), then ~/.cache/shatter/node/node_modules/three; nullopt when none holds
// every file of kViewerFiles at that version. `why` (when given) says where it looked.
std::optional<std::string> find_viewer(std::string* why = nullptr);

struct ReportPageInput {
    std::string name;                 // NAME of the run's files
    nlohmann::ordered_json summary;   // summary.json
    nlohmann::ordered_json settings;  // the shot's settings, by section
    std::string glb;                  // the bytes of NAME.glb ("" when there is none)
    bool viewer = false;              // OUT/viewer/ holds kViewerFiles
    std::string viewer_missing;       // when !viewer: why (shown in the page)
};

std::string report_page_html(const ReportPageInput& input);

// OUT/report.times.js: window.shatterStageTimes = [{"stage", "outcome", "seconds", "last_ran_s"}...];
// `stages` is [{"stage", "outcome", "seconds"}] of this run; `previous` the file's old text ("" if
// none), from which a stage skipped now keeps the time it took when it last ran.
std::string report_times_js(const nlohmann::ordered_json& stages, const std::string& previous);

// ---- the run's report stage (pipeline/run.cpp), after summary.json

// The shot's settings by section, as the stages read them.
nlohmann::ordered_json shot_settings(const Shot& shot);
// What the page depends on, for the stage's key: the summary, the settings, NAME.glb's hash, and
// the viewer found (its files' hashes) or where it was looked for.
nlohmann::ordered_json report_stage_inputs(const std::string& dir, const std::string& name, const Shot& shot,
                                           const nlohmann::ordered_json& summary);
// The files the stage writes, relative to the output folder: report.html and, when the viewer is
// found, viewer/FILE for each of kViewerFiles.
std::vector<std::string> report_stage_outputs();
// Copies the viewer into DIR/viewer/ (or removes a stale copy when there is none) and writes
// DIR/report.html, each file atomically. Throws Error(BadInput) when there is no summary yet.
void write_report(const std::string& dir, const std::string& name, const Shot& shot, const nlohmann::ordered_json& summary);
// DIR/report.times.js from the stages of this run (and the times of the file it replaces).
void write_report_times(const std::string& dir, const std::vector<StageReport>& stages);

}  // namespace shatter
