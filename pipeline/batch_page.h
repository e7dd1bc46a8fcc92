// OUTPUT/index.html, the page of one `shatter batch`: per job its runs as rows (the settings the
// run changes, breaks, fragments, energies, a thumbnail: the frame its sweep's strip shows, and a
// link to the run's report.html) and, per sweep, the strip, the energy plot and the table. A
// failed run is a row with its exit code and last error line. Every number taken from a run's
// summary.json carries data-key (the JSON pointer into it) and data-value (the exact JSON value),
// and each row data-run (JOB/LABEL), so that a test can compare them. No run times: the page is
// the same bytes for the same runs (times are in each run's report.times.js).
#pragma once

#include <string>

#include "pipeline/batch.h"
#include "pipeline/batch_file.h"

namespace shatter {

std::string batch_page_html(const BatchFile& batch, const BatchResult& result);

}  // namespace shatter
