// A piece's deepest point inside what it touches in a step (BulletWorld::last_step_deepest_contact,
// SimulationResult::deepest).
#pragma once

#include <cstdint>

namespace shatter {

struct DeepContact {
    double depth_per_radius = 0;  // depth over the piece's radius (unit: 1)
    double depth = 0;             // (unit: m)
    uint32_t piece = 0;
};

}  // namespace shatter
