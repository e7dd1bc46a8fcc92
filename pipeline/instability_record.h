// NAME.instability.json: what simulate's instability guard ([simulate] on_instability,
// simulate/instability.h) did in a `shatter run`, written by the run's simulate stage next to the
// trajectory (stamped and cached with it), so that summary.json and the closing summary can say
// it when simulate is up to date or comes from the shared cache (docs/reliability.md, section 6).
//
//   {"on_instability": "stop" | "clamp",
//    "clamps": N,              // steps whose velocities were scaled down to the energy limit
//    "first_clamp": EVENT,     // null when N = 0
//    "stopped": EVENT}         // null unless the run stopped (the trajectory is then incomplete)
//   EVENT = {"time_s", "piece", "constraint", "last_broken_constraint", "what"}
//
// "piece", "constraint" and "last_broken_constraint" are the ones simulate's guard names
// (SimulationResult's InstabilityWhere: the first non-finite or the fastest piece, the
// constraint with the largest load for its strength, the one broken last), null when it names
// none; "what" is its message.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "core/scene_settings.h"

namespace shatter {

struct SimulationResult;

nlohmann::ordered_json instability_record(InstabilityMode mode, const SimulationResult& sim);

// Reads a record back; throws Error(BadInput) naming `source` when it is not one.
nlohmann::ordered_json parse_instability_record(std::string_view bytes, const std::string& source);

// "at t = 0.0667 s, piece 13, constraint 33" for an event.
std::string instability_where(const nlohmann::ordered_json& event);

// "velocities clamped in 3 steps".
std::string clamped_steps(uint64_t n);

// The closing summary's "stability:" lines: when the run clamped or stopped, or clamp was asked
// for; empty otherwise.
std::string format_instability(const nlohmann::ordered_json& record);

}  // namespace shatter
