// Figures a run produces that no law predicts (how many joints a scene breaks, its fragments, the
// steps the automatic step takes), pinned in tests/pins/figures.tsv with their tolerance, one row
// each: NAME <tab> VALUE <tab> TOLERANCE (relative, of the pinned value; 0: exact).
//
// A test checks the outcome physics predicts with its own assertions and the run's own figures
// here, so that a change of behaviour moves this file, not the test's code:
//     expect_pinned("paper_scenes.beam.breaks", breaks, 0);
// With SHATTER_UPDATE_FIGURES set, the figure is written into the file instead (its tolerance kept,
// or the one given for a new row), and `make refresh` (scripts/refresh.py) lists what moved.
// Tests run in parallel: the file is rewritten under an exclusive lock, in place of the old one.
#pragma once

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace shatter::testing_support {

inline const char* pinned_figures_file() { return SHATTER_SOURCE_DIR "/tests/pins/figures.tsv"; }

// name -> (value, tolerance), from the file's text.
inline std::map<std::string, std::pair<double, double>> parse_pinned_figures(const std::string& text) {
    std::map<std::string, std::pair<double, double>> rows;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream row(line);
        std::string name, value, tolerance;
        if (std::getline(row, name, '\t') && std::getline(row, value, '\t') && std::getline(row, tolerance))
            rows[name] = {std::strtod(value.c_str(), nullptr), std::strtod(tolerance.c_str(), nullptr)};
    }
    return rows;
}

// Writes `value` as the pinned figure `name` (SHATTER_UPDATE_FIGURES).
inline void update_pinned(const std::string& name, double value, double tolerance) {
    const std::string path = pinned_figures_file();
    const int lock = ::open((path + ".lock").c_str(), O_CREAT | O_RDWR, 0644);
    ASSERT_GE(lock, 0) << "cannot open " << path << ".lock";
    ::flock(lock, LOCK_EX);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    auto rows = parse_pinned_figures(text.str());
    const auto old = rows.find(name);
    rows[name] = {value, old != rows.end() ? old->second.second : tolerance};
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp);
        out << "# Figures tests pin from their runs (tests/support/pinned_figures.h): name, value, relative "
               "tolerance.\n# Re-made by `make refresh`; a change here is a change of behaviour.\n";
        for (const auto& [n, v] : rows) out << n << '\t' << fmt::format("{:.9g}", v.first) << '\t' << v.second << '\n';
    }
    std::rename(tmp.c_str(), path.c_str());
    ::flock(lock, LOCK_UN);
    ::close(lock);
}

// Expects `value` within the pinned figure's tolerance, or re-pins it (SHATTER_UPDATE_FIGURES).
// `tolerance` is used for a figure not pinned yet.
inline void expect_pinned(const std::string& name, double value, double tolerance = 0) {
    if (std::getenv("SHATTER_UPDATE_FIGURES")) {
        update_pinned(name, value, tolerance);
        return;
    }
    std::ifstream in(pinned_figures_file());
    std::stringstream text;
    text << in.rdbuf();
    const auto rows = parse_pinned_figures(text.str());
    const auto it = rows.find(name);
    ASSERT_NE(it, rows.end()) << name << " is not pinned in tests/pins/figures.tsv: make refresh pins it";
    const auto [pinned, tol] = it->second;
    EXPECT_LE(std::abs(value - pinned), tol * std::abs(pinned))
        << name << " = " << fmt::format("{:.9g}", value) << ", pinned " << fmt::format("{:.9g}", pinned)
        << " (tolerance " << 100 * tol << "%). If the change of behaviour is intended, `make refresh` re-pins it";
}

}  // namespace shatter::testing_support
