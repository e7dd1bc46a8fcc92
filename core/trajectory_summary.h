// What `shatter info` says about a trajectory: frames, frame rate, duration, bodies, whether the
// simulation ran to the end, the settings that made it, and per piece how far it travelled, its
// fastest motion between two frames and where it ended.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "core/trajectory.h"

namespace shatter {

nlohmann::ordered_json trajectory_summary(const Trajectory& t);
// The same as an aligned text report.
std::string trajectory_summary_text(const nlohmann::ordered_json& summary);

}  // namespace shatter
