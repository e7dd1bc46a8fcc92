// Energy plots (PNG) drawn by matplotlib through Debian's /usr/bin/python3 (else python3 on PATH
// that has matplotlib). The script is built in; the CSVs are read and checked here and the
// numbers reach the script as JSON on its stdin, never through a command string. Fixed size
// (800x450 pixels) and no version text in the file: the same data gives the same bytes.
#pragma once

#include <string>
#include <vector>

namespace shatter {

struct EnergyCurve {
    std::string label;     // legend entry, e.g. "alpha = 0.5"
    std::string csv_path;  // an energy CSV written by simulate (simulate/recording.h)
};

// One run (one curve given): kinetic, potential (relative to t = 0), stored and injected energy
// against time. Several runs: one kinetic-energy curve per run, plus the injected energy dashed.
// Written to a temporary name and renamed into place. Throws Error(BadInput) with file:line for a
// missing or malformed CSV (before Python starts), Error(Tool) naming the fix when python3 or
// matplotlib is missing or the script fails, Error(Io) when the PNG cannot be written.
void plot_energy(const std::vector<EnergyCurve>& curves, const std::string& title, const std::string& png_path);

}  // namespace shatter
