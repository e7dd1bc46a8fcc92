// The paper's box scenes ("Energized Rigid Body Fracture", Li et al. 2018, section 5) as models
// built from exact boxes: the pre-scored beam, the plate of cubes and the chain between two end
// cubes. The shot's [generate] section chooses one (core/generate_settings.h describes the
// geometry and frame); docs/scenes.md gives the materials and the measured results.
#pragma once

#include "core/generate_settings.h"
#include "core/model.h"

namespace shatter {

// The model `g` describes. Its settings_json records `g` (same settings, same bytes), and its
// tet mesh holds one vertex per constraint (the pivots) and no tets.
Model generate_model(const GenerateSettings& g);

}  // namespace shatter
