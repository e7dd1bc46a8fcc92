// Runs the built-in shots of assets/ the way `shatter run` does (shot -> prescore_shot ->
// simulate), shortened, and measures what the physics tests ask about.
#pragma once

#include <algorithm>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "core/shot.h"
#include "prescore/prescore.h"
#include "simulate/simulate.h"

namespace shatter::scenes_test {

inline Shot asset(const std::string& name) { return load_shot(SHATTER_SOURCE_DIR "/assets/" + name + ".toml"); }

inline SimulationInput input_of(const Shot& shot, double alpha, double duration) {
    SimulationInput in{shot.scene, shot.object, shot.material, shot.simulate};
    in.material.alpha = alpha;
    in.simulate.duration = duration;
    return in;
}

// The kinetic energy of the pieces at the first recorded frame at or after time t (unit: J).
inline double kinetic_at(const SimulationResult& r, double t) {
    for (const EnergySample& e : r.energy)
        if (e.time >= t - 1e-9) return e.kinetic;
    return r.energy.back().kinetic;
}

// The pieces that unbroken constraints still hold together: the number of connected groups.
inline size_t fragments(const Model& model, const SimulationResult& r) { return count_fragments(model, r.breaks); }

inline Vec3 position(const SimulationResult& r, uint32_t frame, uint32_t body) {
    return r.trajectory.pose(frame, body).position.cast<double>();
}

inline uint32_t frame_at(const SimulationResult& r, double t) {
    return std::min(uint32_t(std::ceil(t * r.trajectory.fps - 1e-9)), r.trajectory.frames() - 1);
}

}  // namespace shatter::scenes_test
