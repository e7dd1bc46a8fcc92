// Fewer constraints per piece pair: the smallest model that serves (the study's "constraints per
// piece pair" knob). A pair's constraints are thinned to at most `max_per_pair` by farthest-point
// sampling over their pivots (starting from the constraint of largest area; ties to the lower
// vertex index), and each dropped constraint's area goes to the nearest kept one, so a pair's
// total area (its stiffness and strength) is unchanged while each constraint carries more.
// Farthest points keep the interface's extent, so the pair still resists bending.
#pragma once

#include <cstdint>
#include <vector>

#include "core/model.h"

namespace shatter {

// `constraints` sorted by (piece_a, piece_b, vertex); max_per_pair 0 keeps all. The result is
// sorted the same way.
std::vector<Constraint> reduce_constraints(const std::vector<Constraint>& constraints, uint32_t max_per_pair);

}  // namespace shatter
