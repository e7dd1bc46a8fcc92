// The numbers a run reports about its fracture (summary.json, batch tables, the scenes' docs):
// breaks, energies, fragments and how fast they part, computed from the stage files.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/model.h"
#include "core/trajectory.h"

namespace shatter {

// {"frames", "fps", "complete", "breaks", "first_break_s", "stored_energy_J", "injected_energy_J",
//  "fragments" (groups of pieces still joined at the end), "kinetic_energy_after_first_break_J"
//  (all pieces, 0.1 s after the first break, from the energy books), "spread_energy_after_first_break_J"
//  (translational kinetic energy relative to the centre of mass of all pieces, 0.1 s after the
//  first break: how hard the fragments fly apart, without the object's common motion),
//  "peak_piece_speed_m_per_s"}. Null where there is no break.
nlohmann::ordered_json simulation_facts(const Model& model, const Trajectory& trajectory, const std::string& breaks_jsonl,
                                        const std::string& energy_csv);

// A warning a run's stage kept in its file, as summary.json lists it.
struct StageWarning {
    const char* stage;  // "prescore" or "simulate"
    std::string text;
};

// The warnings of a run's summary.json (either JSON type: the pages read it as either): prescore's
// under "model"/"warnings", then simulate's under "simulation"/"warnings", in order.
template <class Json>
std::vector<StageWarning> summary_warnings(const Json& summary) {
    std::vector<StageWarning> out;
    for (const auto& [part, stage] : {std::pair{"model", "prescore"}, std::pair{"simulation", "simulate"}}) {
        const auto p = summary.find(part);
        if (p == summary.end()) continue;
        const auto w = p->find("warnings");
        if (w == p->end()) continue;
        for (const auto& text : *w)
            if (text.is_string()) out.push_back({stage, text.template get<std::string>()});
    }
    return out;
}

}  // namespace shatter
