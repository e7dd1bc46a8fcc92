#include "pipeline/run_metrics.h"

#include "core/error.h"
#include "core/fragments.h"
#include "pipeline/energy_csv.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

namespace shatter {

using json = nlohmann::ordered_json;

nlohmann::ordered_json simulation_facts(const Model& model, const Trajectory& traj, const std::string& breaks_jsonl,
                                        const std::string& energy_csv_text) {
    // Breaks: count, energies, and which constraints are gone.
    std::vector<bool> broken(model.constraints.size(), false);
    size_t breaks = 0;
    double stored = 0, injected = 0, held = 0, first_break = -1;
    std::istringstream lines(breaks_jsonl);
    size_t line_no = 0;
    for (std::string line; std::getline(lines, line);) {
        ++line_no;
        if (line.empty()) continue;
        // A damaged log is bad input, not a bug (found by tests/fuzz/logs_fuzz.cpp).
        try {
            const nlohmann::json b = nlohmann::json::parse(line);
            ++breaks;
            stored += b.at("stored_energy_J").get<double>();
            injected += b.at("injected_energy_J").get<double>();
            held += b.value("held_energy_J", 0.0) - b.value("released_energy_J", 0.0);
            if (first_break < 0) first_break = b.at("time_s").get<double>();
            const uint32_t c = b.at("constraint").get<uint32_t>();
            if (c < broken.size()) broken[c] = true;
        } catch (const nlohmann::json::exception& e) {
            throw_input_error("break log line " + std::to_string(line_no), e.what(),
                              "simulate again (shatter run --force --stages simulate)");
        }
    }
    const size_t fragments = count_fragments(model, broken);

    const EnergySeries energy = parse_energy_csv(energy_csv_text, "energy CSV");
    // Kinetic energy 0.1 s after the first break, from the energy books.
    std::optional<double> kinetic_after;
    if (first_break >= 0) {
        double best = 1e300;
        for (size_t i = 0; i < energy.t.size(); ++i)
            if (std::abs(energy.t[i] - (first_break + 0.1)) < best)
                best = std::abs(energy.t[i] - (first_break + 0.1)), kinetic_after = energy.kinetic[i];
    }
    // The largest joint residual of any step (the energy books' joint_residual column, each row
    // the largest of its frame's steps) and when; absent from files of older versions.
    std::optional<double> residual, residual_at;
    for (size_t i = 0; i < energy.joint_residual.size(); ++i)
        if (!residual || energy.joint_residual[i] > *residual) residual = energy.joint_residual[i], residual_at = energy.t[i];
    // Peak piece speed between recorded frames.
    double peak_speed = 0;
    for (uint32_t f = 1; f < traj.frames(); ++f)
        for (uint32_t b = 0; b < traj.pieces; ++b)
            peak_speed = std::max(peak_speed, double((traj.pose(f, b).position - traj.pose(f - 1, b).position).norm()) * traj.fps);

    json j;
    j["frames"] = traj.frames();
    j["fps"] = traj.fps;
    j["complete"] = traj.complete;
    j["breaks"] = breaks;
    j["first_break_s"] = first_break >= 0 ? json(first_break) : json(nullptr);
    j["stored_energy_J"] = stored;
    j["injected_energy_J"] = injected;
    // alpha E of breaks inside pieces still joined at the end (cracks that never opened).
    j["held_energy_J"] = held;
    j["fragments"] = fragments;
    j["kinetic_energy_after_first_break_J"] = kinetic_after ? json(*kinetic_after) : json(nullptr);
    j["spread_energy_after_first_break_J"] =
        first_break >= 0 ? json(spread_energy(model, traj, uint32_t(std::lround((first_break + 0.1) * traj.fps))))
                         : json(nullptr);
    j["peak_piece_speed_m_per_s"] = peak_speed;
    j["joint_residual_max"] = residual ? json(*residual) : json(nullptr);
    j["joint_residual_frame_s"] = residual_at ? json(*residual_at) : json(nullptr);
    // How far the energy books (docs/physics.md section 5c) moved over the run: round-off when
    // every term is counted; absent from files of older versions.
    if (!energy.books.empty()) {
        const auto [lo, hi] = std::minmax_element(energy.books.begin(), energy.books.end());
        j["energy_books_drift_J"] = *hi - *lo;
    }
    return j;
}


}  // namespace shatter
