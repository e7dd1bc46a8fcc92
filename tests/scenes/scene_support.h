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
inline size_t fragments(const Model& model, const SimulationResult& r) {
    std::vector<uint32_t> parent(model.pieces.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    std::vector<char> broken(model.constraints.size(), 0);
    for (const BreakRecord& b : r.breaks) broken[b.constraint] = 1;
    for (size_t c = 0; c < model.constraints.size(); ++c)
        if (!broken[c]) parent[find(model.constraints[c].piece_a)] = find(model.constraints[c].piece_b);
    size_t groups = 0;
    for (uint32_t p = 0; p < parent.size(); ++p) groups += find(p) == p;
    return groups;
}

inline Vec3 position(const SimulationResult& r, uint32_t frame, uint32_t body) {
    return r.trajectory.pose(frame, body).position.cast<double>();
}

inline uint32_t frame_at(const SimulationResult& r, double t) {
    return std::min(uint32_t(std::ceil(t * r.trajectory.fps - 1e-9)), r.trajectory.frames() - 1);
}

}  // namespace shatter::scenes_test
