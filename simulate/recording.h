// The text outputs of simulate beside the trajectory (docs/formats.md):
//   OUT.breaks.jsonl  one JSON object per break, in time order
//   OUT.energy.csv    the energy books per recorded frame
#pragma once

#include <string>
#include <vector>

#include "simulate/simulate.h"

namespace shatter {

std::string break_log_jsonl(const std::vector<BreakRecord>& breaks);
std::string energy_csv(const std::vector<EnergySample>& samples);

}  // namespace shatter
