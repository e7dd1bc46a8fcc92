#include "simulate/breaking.h"

#include <cmath>

namespace shatter {

std::vector<Overload> find_overloads(BulletWorld& world, BreakCriterion criterion) {
    std::vector<Overload> over;
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        if (!world.active(c)) continue;
        const double f = world.force_on_a(c).norm();
        const double ratio = world.strength(c) > 0 ? f / world.strength(c) : INFINITY;
        if (criterion == BreakCriterion::BulletImpulse) {
            if (!world.bullet_disabled(c)) continue;
            world.enable(c);
        } else if (!(f > world.strength(c))) {
            continue;
        }
        over.push_back({c, ratio});
    }
    return over;
}

uint64_t break_key(uint64_t seed, size_t constraint) {
    uint64_t z = seed + 0x9e3779b97f4a7c15ull * (constraint + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    return z ^ (z >> 27);
}

BreakRecord energize_broken(BulletWorld& world, size_t c, const std::array<BodyAtPivot, 2>& load,
                            const EnergizeSettings& settings, uint64_t key, std::optional<Vec3> frame_velocity) {
    Vec3 pivot;
    std::array<BodyAtPivot, 2> now = world.bodies_at_pivot(c, &pivot);
    for (int s = 0; s < 2; ++s) {
        now[s].force = load[s].force;
        now[s].torque = load[s].torque;
    }
    BreakRecord r;
    r.time = world.time();
    r.constraint = uint32_t(c);
    r.piece_a = world.piece_a(c);
    r.piece_b = world.piece_b(c);
    r.pivot = pivot;
    r.force = load[0].force;
    r.strength = world.strength(c);
    r.stiffness = world.stiffness(c);
    r.alpha = settings.alpha;
    const Vec3 frame = frame_velocity ? *frame_velocity : pair_frame_velocity(load[0], load[1]);
    r.kicks = energize(now[0], now[1], r.stiffness, settings, key, frame);
    const double before = world.kinetic_energy_of_pair(c, frame), before_world = world.kinetic_energy_of_pair(c);
    world.apply_kicks(c, pivot, r.kicks);
    r.injected_energy = world.kinetic_energy_of_pair(c, frame) - before;
    r.momentum_work = world.kinetic_energy_of_pair(c) - before_world - r.injected_energy;
    return r;
}

}  // namespace shatter
