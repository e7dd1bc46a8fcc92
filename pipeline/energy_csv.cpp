#include "pipeline/energy_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace shatter {

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> out(1);
    for (char c : line) {
        if (c == sep)
            out.emplace_back();
        else if (c != '\r')
            out.back() += c;
    }
    return out;
}

}  // namespace

EnergySeries parse_energy_csv(const std::string& text, const std::string& path) {
    std::vector<std::string> lines = split(text, '\n');
    if (!lines.empty() && lines.back().empty()) lines.pop_back();
    const char* fix = "give an energy CSV written by shatter simulate (OUT.energy.csv)";
    if (lines.empty()) throw_input_error(path, "empty energy CSV", fix);
    const std::vector<std::string> header = split(lines[0], ',');
    // The first five columns are needed; older files lack the later ones: elastic_J, then the
    // books' other four (read only when all of them are there), then integration_J (0 without).
    const char* names[] = {"time_s",    "kinetic_J", "potential_J",     "stored_J",   "injected_J", "elastic_J",
                           "removed_J", "joints_damped_J", "contacts_J", "driven_J", "integration_J"};
    constexpr int kNeeded = 5, kBooks = 10, kAll = 11;
    size_t column[kAll];
    int columns = kAll;
    for (int k = 0; k < kAll; ++k) {
        auto it = std::find(header.begin(), header.end(), names[k]);
        if (it == header.end() && k < kNeeded)
            throw_input_error(path + ":1", fmt::format("header '{}' has no column {}", lines[0], names[k]), fix);
        if (it == header.end()) {
            columns = k == kNeeded ? kNeeded : k < kBooks ? kNeeded + 1 : kBooks;
            break;
        }
        column[k] = size_t(it - header.begin());
    }
    const auto residual_column = std::find(header.begin(), header.end(), "joint_residual");
    EnergySeries s;
    std::vector<double>* series[] = {&s.t, &s.kinetic, &s.potential, &s.stored, &s.injected, &s.elastic};
    for (size_t i = 1; i < lines.size(); ++i) {
        const std::string where = fmt::format("{}:{}", path, i + 1);
        const std::vector<std::string> fields = split(lines[i], ',');
        if (fields.size() != header.size())
            throw_input_error(where, fmt::format("{} fields where the header has {}", fields.size(), header.size()),
                              fix);
        const auto number = [&](size_t at, const char* name) {
            const std::string& f = fields[at];
            double v = 0;
            auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
            if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v))
                throw_input_error(where, fmt::format("{} '{}' is not a finite number", name, f), fix);
            return v;
        };
        double v[kAll];
        for (int k = 0; k < columns; ++k) {
            v[k] = number(column[k], names[k]);
            if (k <= kNeeded) series[k]->push_back(v[k]);
        }
        if (residual_column != header.end())
            s.joint_residual.push_back(number(size_t(residual_column - header.begin()), "joint_residual"));
        if (columns >= kBooks) {
            // kinetic + potential + elastic + removed + joints_damped + contacts + integration -
            // injected - driven
            const double integration = columns == kAll ? v[10] : 0.0;
            s.books.push_back(v[1] + v[2] + v[5] + v[6] + v[7] + v[8] + integration - v[4] - v[9]);
            s.joints_took.push_back(v[6] + v[7]);
            s.contacts_took.push_back(v[8] + integration);
            s.driven.push_back(v[9]);
        }
    }
    if (s.t.empty()) throw_input_error(path, "the energy CSV has a header but no samples", fix);
    return s;
}

}  // namespace shatter
