// `shatter diff EXPECTED ACTUAL`: two PNG images, or two directories of frames (every *.png of
// either; the two must hold the same names). For each pair the metrics of render/image_diff.h
// against a tolerance; a heat map per failing pair; a JSON summary; a JUnit XML report on
// request (one test case per image, for CI dashboards).
//
// A missing frame, a size mismatch and an unreadable image are errors (Error, BadInput), not
// differences: the command exits 2 for them and 1 only for images that differ.
#pragma once

#include <string>
#include <vector>

#include "render/image_diff.h"

namespace shatter {

struct ImageDiff {
    std::string name;      // the file name (the path when comparing two files)
    DiffMetrics metrics;
    std::vector<std::string> failures;  // empty: within tolerance
    std::string heat_map;  // path of the heat map written for a failing pair, else ""
};

struct DiffSummary {
    std::string expected, actual;
    DiffTolerance tolerance;
    std::vector<ImageDiff> images;  // sorted by name
    size_t failed = 0;
};

// Compares; writes heat maps of failing pairs into `report_dir` (created when needed; "" writes
// none). Throws Error(BadInput) for a missing frame, a size mismatch or an unreadable image.
DiffSummary diff_paths(const std::string& expected, const std::string& actual, const DiffTolerance& tolerance,
                       const std::string& report_dir);

std::string diff_summary_json(const DiffSummary& s);
std::string diff_junit_xml(const DiffSummary& s);

}  // namespace shatter
