// REPORT_DIR/report.html of `shatter diff`, beside its summary.json and heat maps, for a person
// or a CI system's artifact viewer: the tolerances; per failing image its expected and actual
// images and heat map side by side, the two stacked with a slider (drag to uncover the actual)
// and a blink toggle, its metrics and the bounds it breaks; then every image's metrics in a
// table. The failing images' expected and actual are copied into REPORT_DIR (NAME.expected.png,
// NAME.actual.png, beside NAME.heat.png), so that the folder is complete on its own when archived.
// Every number carries data-key (a JSON pointer into the report's summary.json) and data-value
// (its exact JSON value), for tests. Deterministic: no times.
#pragma once

#include <string>

#include "render/diff_report.h"

namespace shatter {

// The page; `summary_json` is diff_summary_json(s), whose values the page shows.
std::string diff_page_html(const DiffSummary& s, const std::string& summary_json);

// Copies the failing images into `report_dir` and writes report_dir/report.html, each file
// atomically; returns the page's path.
std::string write_diff_page(const DiffSummary& s, const std::string& report_dir);

}  // namespace shatter
