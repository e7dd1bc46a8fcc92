// The numbers a run reports about its fracture (summary.json, batch tables, the scenes' docs):
// breaks, energies, fragments and how fast they part, computed from the stage files.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

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

}  // namespace shatter
