// How the fragments of a run move: measures on a model and its trajectory, shared by the
// pipeline's summaries (pipeline/run_metrics.h), the scenes' tests and the study.
// (count_fragments, on a model alone, is in core/model.h.)
#pragma once

#include <cstdint>

#include "core/model.h"
#include "core/trajectory.h"

namespace shatter {

// Translational kinetic energy of the pieces relative to their common centre of mass at frame f
// (velocities by central differences of the recorded positions; f is clamped to [1, frames - 2]):
// how hard the fragments fly apart, without the object's common motion (unit: J).
double spread_energy(const Model& model, const Trajectory& t, uint32_t f);

}  // namespace shatter
