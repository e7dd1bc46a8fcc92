// Energy plots (PNG, 800x450 pixels), drawn in-process by pipeline/line_chart.h: no interpreter
// to start beside render, and the same data gives the same bytes.
#pragma once

#include <string>
#include <vector>

namespace shatter {

struct EnergyCurve {
    std::string label;     // legend entry, e.g. "alpha = 0.5"
    std::string csv_path;  // an energy CSV written by simulate (simulate/recording.h)
};

// One run (one curve given): every term of its energy books against time (kinetic, potential
// relative to t = 0, stored, elastic, injected, what the joints and the contacts took, what driven
// pieces gave) and their sum. Several runs: one kinetic-energy curve per run, its injected energy
// dashed. Written to a temporary name and renamed into place. Throws Error(BadInput) with
// file:line for a missing or malformed CSV (nothing written), Error(Io) when the PNG cannot be
// written.
void plot_energy(const std::vector<EnergyCurve>& curves, const std::string& title, const std::string& png_path);

}  // namespace shatter
